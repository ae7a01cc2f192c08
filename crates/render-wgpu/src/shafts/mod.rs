//! Light in the air cut by shadows: the local light beams of lights through a
//! homogeneous medium ([`beams`]).

pub mod beams;
