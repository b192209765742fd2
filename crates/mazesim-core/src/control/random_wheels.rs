//! Uniform random wheel speeds, from each environment's own seeded stream: the `random` workload.

use crate::rng::Rng;

/// Wheel speeds (left, right), each uniform in `[-max_speed, max_speed)`: two draws of `stream`,
/// left first.
pub fn wheel_speeds(stream: &mut Rng, max_speed: f64) -> [f32; 2] {
    let mut draw = || (max_speed * (2.0 * stream.uniform() - 1.0)) as f32;
    let left = draw();
    [left, draw()]
}

#[cfg(test)]
#[allow(clippy::approx_constant)] // 6.28 rad/s is the e-puck motor limit, not tau.
mod tests {
    use super::*;

    #[test]
    fn speeds_cover_both_directions_within_the_limit() {
        let mut stream = Rng::new(7);
        let speeds: Vec<[f32; 2]> = (0..1000).map(|_| wheel_speeds(&mut stream, 6.28)).collect();
        assert!(speeds.iter().flatten().all(|w| w.abs() <= 6.28));
        assert!(speeds.iter().any(|w| w[0] < -5.0) && speeds.iter().any(|w| w[1] > 5.0));
        let again: Vec<[f32; 2]> = {
            let mut s = Rng::new(7);
            (0..1000).map(|_| wheel_speeds(&mut s, 6.28)).collect()
        };
        assert_eq!(speeds, again);
    }
}
