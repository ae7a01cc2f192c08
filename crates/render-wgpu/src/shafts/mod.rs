//! Light in the air cut by shadows: the local light beams of lights through a
//! homogeneous medium ([`beams`]), and the planet's light shafts, the terrain's shadow
//! in the air ([`terrain`]).

pub mod beams;
pub mod terrain;
