//! The Braitenberg rule of the benchmark workload (`mazesim.benchmark.braitenberg`), in the same
//! float32 arithmetic as numpy computes it, so that both give the same wheel speeds bit for bit.

/// Reading of ps0..ps7 at which a sensor starts to count (the e-puck table's value at 7 cm).
const FLOOR: f32 = 67.19;
/// Readings above `FLOOR` that make a sensor's activation 1.
const SPAN: f32 = 300.0;
/// The wheel speed limit of the rule, rad/s (the e-puck's motor limit, not 2 pi).
#[allow(clippy::approx_constant)]
const LIMIT: f32 = 6.28;

/// Wheel speeds (left, right) in rad/s from the eight e-puck proximity readings ps0..ps7.
///
/// Each side's activation turns the robot away from that side, and a frontal obstacle turns it
/// left so that it never stalls square to a wall. Every operation is a float32 operation in
/// numpy's order (`0.7 * a` is `0.7f32 * a`), with no fused multiply-add.
pub fn wheel_speeds(ps: &[f32]) -> [f32; 2] {
    let a = |i: usize| ((ps[i] - FLOOR) / SPAN).clamp(0.0, 1.0);
    let right_side = a(0) + 0.7 * a(1) + 0.4 * a(2);
    let left_side = a(7) + 0.7 * a(6) + 0.4 * a(5);
    let front = 0.5 * (a(0) + a(7));
    let base = 5.0 * (1.0 - front);
    let turn = 4.0 * (right_side - left_side) + 6.0 * front;
    [
        (base - turn).clamp(-LIMIT, LIMIT),
        (base + turn).clamp(-LIMIT, LIMIT),
    ]
}

#[cfg(test)]
#[allow(clippy::approx_constant)] // 6.28 rad/s is the e-puck motor limit, not tau.
mod tests {
    use super::*;

    #[test]
    fn drives_straight_in_the_open_and_turns_away_from_walls() {
        let open = [60.0f32; 8];
        assert_eq!(wheel_speeds(&open), [5.0, 5.0]);
        let mut right_wall = open;
        right_wall[1] = 400.0;
        let [l, r] = wheel_speeds(&right_wall);
        assert!(l < r, "a wall on the right turns left: {l} {r}");
        let mut ahead = open;
        ahead[0] = 4095.0;
        ahead[7] = 4095.0;
        let [l, r] = wheel_speeds(&ahead);
        assert!(l < 0.0 && r > 0.0, "a wall ahead spins left: {l} {r}");
        assert!(l >= -LIMIT && r <= LIMIT);
    }
}
