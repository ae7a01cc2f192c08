//! Where light of order two and up is scattered towards the camera for the last time: a
//! node of the view ray (mass = quadrature weight x transmittance x scattering
//! coefficient) or the ground where the ray ends (mass = transmittance x albedo), and the
//! probability of drawing each.
//!
//! Without guiding each is drawn in proportion to its mass. With guiding, where any of
//! them lies in the planet's umbra, the events are cut into groups short in altitude and
//! distance, each with a [`DirectionGuide`] built at its middle; half the probability
//! then follows the mass and half the mass times the light the group's guide expects to
//! arrive there, phase-weighted towards the camera. In deep twilight that light grows by
//! orders of magnitude with altitude (high air is closer to the sunlit air), so the high
//! nodes that carry most of it are drawn as often as they matter. Either way a drawn
//! event's value is divided by its probability, so the expected value stays the same.

use glam::DVec3;

use crate::reference::guide::{DirectionGuide, ExpectedLight};
use crate::reference::path_tracer::PathTracer;
use crate::reference::scatterer::Scatterer;

/// Largest change of altitude within a group, m.
const GROUP_HEIGHT_M: f64 = 4_000.0;
/// Largest distance along the ray within a group, m.
const GROUP_LENGTH_M: f64 = 100_000.0;
/// Share of the probability that follows the mass alone when guiding, for the light the
/// guides leave out (higher orders, the penumbra).
const MASS_SHARE: f64 = 0.5;

/// One place of last scattering.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LastEvent {
    pub position: DVec3,
    pub scatterer: Scatterer,
    pub mass: f64,
}

/// The events with their probabilities and guides.
#[derive(Debug)]
pub(crate) struct LastEvents {
    events: Vec<LastEvent>,
    /// Cumulative probability at the end of each event.
    cdf: Vec<f64>,
    /// Mass over probability of each event.
    weight: Vec<f64>,
    /// Each event's guide, an index into `guides`.
    group: Vec<usize>,
    guides: Vec<Option<DirectionGuide>>,
}

impl LastEvents {
    /// The events seen along `view_direction`, guided (when `guided`, and some event is
    /// in the umbra) or not. `None` where no event has mass.
    pub fn new(
        events: Vec<LastEvent>,
        view_direction: DVec3,
        tracer: &PathTracer<'_>,
        guided: bool,
    ) -> Option<LastEvents> {
        let total: f64 = events.iter().map(|e| e.mass).sum();
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let guided = guided && events.iter().any(|e| tracer.in_umbra(e.position));
        let (group, guides) = if guided {
            group_and_guide(&events, tracer)
        } else {
            (vec![0; events.len()], vec![None])
        };
        // The light each group's guide expects at its events, towards the camera.
        let per_group: Vec<Option<ExpectedLight>> = guides
            .iter()
            .map(|g| {
                g.as_ref()
                    .map(|g| g.expected(view_direction, &tracer.atmosphere.mie.phase))
            })
            .collect();
        let expected: Vec<f64> = events
            .iter()
            .zip(&group)
            .map(|(e, g)| per_group[*g].map_or(0.0, |x| x.scattered_by(e.scatterer)))
            .collect();
        let lit_total: f64 = events.iter().zip(&expected).map(|(e, x)| e.mass * x).sum();
        let mass_share = if lit_total > 0.0 { MASS_SHARE } else { 1.0 };
        let probability: Vec<f64> = events
            .iter()
            .zip(&expected)
            .map(|(e, x)| {
                let lit = if lit_total > 0.0 {
                    e.mass * x / lit_total
                } else {
                    0.0
                };
                mass_share * e.mass / total + (1.0 - mass_share) * lit
            })
            .collect();
        let mut acc = 0.0;
        let cdf = probability
            .iter()
            .map(|p| {
                acc += p;
                acc
            })
            .collect();
        let weight = events
            .iter()
            .zip(&probability)
            .map(|(e, p)| if *p > 0.0 { e.mass / p } else { 0.0 })
            .collect();
        Some(LastEvents {
            events,
            cdf,
            weight,
            group,
            guides,
        })
    }

    /// Whether any event has a guide towards sunlit air.
    pub fn is_guided(&self) -> bool {
        self.guides.iter().any(Option::is_some)
    }

    /// The event at the uniform number `u`, its mass over its probability, and its guide.
    pub fn draw(&self, u: f64) -> (&LastEvent, f64, Option<&DirectionGuide>) {
        let end = *self.cdf.last().unwrap_or(&1.0);
        let i = self
            .cdf
            .partition_point(|c| *c < u * end)
            .min(self.events.len() - 1);
        (
            &self.events[i],
            self.weight[i],
            self.guides[self.group[i]].as_ref(),
        )
    }
}

/// Groups of consecutive events within [`GROUP_HEIGHT_M`] of altitude and
/// [`GROUP_LENGTH_M`] of each other (the ground alone), and a guide at each group's middle.
fn group_and_guide(
    events: &[LastEvent],
    tracer: &PathTracer<'_>,
) -> (Vec<usize>, Vec<Option<DirectionGuide>>) {
    let mut group = Vec::with_capacity(events.len());
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut first: Option<&LastEvent> = None;
    for (i, e) in events.iter().enumerate() {
        let starts = match first {
            None => true,
            Some(f) => {
                matches!(e.scatterer, Scatterer::Ground(_))
                    || (e.position.length() - f.position.length()).abs() > GROUP_HEIGHT_M
                    || (e.position - f.position).length() > GROUP_LENGTH_M
            }
        };
        if starts {
            members.push(Vec::new());
            first = Some(e);
        }
        if let Some(m) = members.last_mut() {
            m.push(i);
        }
        group.push(members.len() - 1);
    }
    let guides = members
        .iter()
        .map(|m| {
            let anchor = events[m[m.len() / 2]].position;
            DirectionGuide::new(anchor, tracer.sun_direction, |d| {
                tracer.rough_incoming(anchor, d)
            })
        })
        .collect();
    (group, guides)
}
