// Library: the largest finite f16, the HDR target's ceiling.

const F16_MAX: f32 = 65504.0;
