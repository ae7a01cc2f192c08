//! How many loop trips one GPU shader invocation may run. Mesa's software Vulkan
//! (lavapipe) ends an invocation's loops, all of them together, once they have run 65535
//! trips, and says nothing: the answer is silently wrong. Settings whose shaders would
//! run more than [`MAX_LOOP_TRIPS`] in one invocation are refused; the rest of 65535 is
//! left for the loops no setting counts.

use crate::models::error::ModelError;

/// The most loop trips the settings may ask of one GPU invocation.
pub const MAX_LOOP_TRIPS: usize = 32768;

/// Nothing, or an error naming `model`, how the trips come from the settings (`what`,
/// e.g. "2 x planes=100 x interval_steps=10") and the limit.
pub fn check_loop_trips(model: &str, what: &str, trips: usize) -> Result<(), ModelError> {
    if trips <= MAX_LOOP_TRIPS {
        return Ok(());
    }
    Err(ModelError::Settings(format!(
        "{model} settings {what} = {trips} loop trips in one GPU invocation, over \
         {MAX_LOOP_TRIPS} (every GPU must run them in full)"
    )))
}
