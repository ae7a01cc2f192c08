//! The planet's shadow on a view ray: where the sun, a point at infinity, is hidden by the
//! ground. A point x is in shadow when it lies behind the planet (x . s < 0) within the
//! cylinder of the planet's radius around the sun's direction s through the centre: the
//! sun ray from x then meets the sphere. The riley model's spherical geometry integrates
//! its closed form over the lit parts of the ray only.

use glam::DVec3;

/// The part `[start, end]` of the ray `origin + t direction`, `0 <= t <= length`, that lies
/// in the shadow of a planet of radius `bottom_m` centred at the origin, lit from the unit
/// direction `sun`; `None` when the ray is lit all along.
pub fn shadowed_interval(
    origin: DVec3,
    direction: DVec3,
    sun: DVec3,
    bottom_m: f64,
    length: f64,
) -> Option<(f64, f64)> {
    let (origin_along, direction_along) = (origin.dot(sun), direction.dot(sun));
    let origin_across = origin - origin_along * sun;
    let direction_across = direction - direction_along * sun;
    // |origin_across + t direction_across|^2 < bottom^2: a t^2 + 2 b t + c < 0.
    let a = direction_across.length_squared();
    let b = origin_across.dot(direction_across);
    let c = (origin_across.length() - bottom_m) * (origin_across.length() + bottom_m);
    let (mut start, mut end) = if a == 0.0 {
        if c >= 0.0 {
            return None;
        }
        (f64::NEG_INFINITY, f64::INFINITY)
    } else {
        let discriminant = b * b - a * c;
        if discriminant <= 0.0 {
            return None;
        }
        // The roots without cancellation: q = -(b + sign(b) sqrt(D)), roots q / a, c / q.
        let q = -(b + b.signum() * discriminant.sqrt());
        let (t1, t2) = if q == 0.0 {
            let half = (-c / a).sqrt();
            (-half, half)
        } else {
            (q / a, c / q)
        };
        (t1.min(t2), t1.max(t2))
    };
    // Behind the planet: origin_along + t direction_along < 0.
    if direction_along > 0.0 {
        end = end.min(-origin_along / direction_along);
    } else if direction_along < 0.0 {
        start = start.max(-origin_along / direction_along);
    } else if origin_along >= 0.0 {
        return None;
    }
    let (start, end) = (start.max(0.0), end.min(length));
    (start < end).then_some((start, end))
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6.36e6;

    /// Whether the sun ray from `x` meets the sphere: the definition of shadow.
    fn in_shadow(x: DVec3, sun: DVec3) -> bool {
        let along = x.dot(sun);
        along < 0.0 && (x - along * sun).length() < R
    }

    /// Points sampled along rays agree with the interval: inside it in shadow, outside lit.
    #[test]
    fn the_interval_is_where_the_sun_ray_meets_the_planet() {
        let sun = DVec3::new(-0.3, 0.2, -0.5).normalize();
        let origins = [
            DVec3::new(0.0, 0.0, R + 2.0),
            DVec3::new(1e5, -2e5, R + 4e5),
            DVec3::new(R + 3e4, 0.0, 0.0),
        ];
        let directions = [
            DVec3::new(0.3, 0.1, 0.9),
            DVec3::new(-0.8, 0.2, 0.1),
            DVec3::new(0.1, -0.9, -0.4),
            DVec3::new(0.5, 0.5, 0.0),
        ];
        let mut seen_both = 0;
        for origin in origins {
            for direction in directions.map(|d| d.normalize()) {
                let length = 2e6;
                let interval = shadowed_interval(origin, direction, sun, R, length);
                let mut states = (false, false);
                for i in 0..=2000 {
                    let t = length * i as f64 / 2000.0;
                    let x = origin + t * direction;
                    if x.length() < R {
                        continue;
                    }
                    let inside = interval.is_some_and(|(a, b)| t > a && t < b);
                    let near_edge =
                        interval.is_some_and(|(a, b)| (t - a).abs() < 1.0 || (t - b).abs() < 1.0);
                    if !near_edge {
                        assert_eq!(inside, in_shadow(x, sun), "{origin} {direction} t {t}");
                    }
                    states = (states.0 || inside, states.1 || !inside);
                }
                seen_both += usize::from(states.0 && states.1);
            }
        }
        assert!(seen_both > 0, "no ray crossed the shadow's edge");
    }

    #[test]
    fn a_ray_on_the_day_side_is_lit() {
        let sun = DVec3::Z;
        let origin = DVec3::new(0.0, 0.0, R + 10.0);
        assert_eq!(shadowed_interval(origin, DVec3::X, sun, R, 1e6), None);
    }
}
