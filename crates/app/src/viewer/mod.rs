//! The interactive viewer (issue 5). Only its window-free logic is here so far: the
//! flight controller. The window, the egui panel and the terrain pass come later.

pub mod flight;
