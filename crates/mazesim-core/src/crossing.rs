//! Ground truth of barcode crossings: which checkpoint's code the barcode sensor actually crossed,
//! in which direction, and when. A crossing is complete when the sensor leaves a code on the
//! opposite end from where it came in; leaving on the same end (turning back on the code) is not
//! a crossing.

use crate::world::Checkpoint;

/// Metres kept between a quiet disc and the nearest code's disc, and by which a point must
/// clear a code's disc to be skipped: far above rounding, so no point on a code is skipped.
const QUIET_MARGIN: f64 = 1e-6;

/// One completed crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Crossing {
    /// The checkpoint's id.
    pub checkpoint: u32,
    /// True when crossed along the checkpoint's yaw (the code reads as written: arriving at the
    /// door it faces); false when crossed the other way (departing).
    pub forward: bool,
    /// Control step (1-based, counted since reset) in which the crossing completed.
    pub step: u64,
}

impl Crossing {
    /// The crossing as one signed number: +id forward, -id reverse.
    pub fn signed_id(&self) -> i32 {
        if self.forward {
            self.checkpoint as i32
        } else {
            -(self.checkpoint as i32)
        }
    }
}

/// Follows one sensor over the codes of a world.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrossingTracker {
    /// The code the sensor is on (index into the world's checkpoints) and the end it came in by
    /// (-1 = the start of the code, +1 = its end).
    on_code: Option<(usize, i8)>,
    /// The sensor's position at the last update or placement, to know the end by which it came
    /// onto a code.
    previous: Option<[f64; 2]>,
    /// A disc (centre, radius) that reaches no code: while the sensor stays in it and on no
    /// code, nothing can happen, and the codes need not be looked at.
    quiet: Option<([f64; 2], f64)>,
}

/// How far `p` is from the disc around a code's corners (negative inside it).
fn beyond_reach(cp: &Checkpoint, p: [f64; 2]) -> f64 {
    let dx = p[0] - cp.center[0];
    let dy = p[1] - cp.center[1];
    (dx * dx + dy * dy).sqrt() - 0.5 * (cp.length * cp.length + cp.width * cp.width).sqrt()
}

/// Where `p` lies in a checkpoint's frame: (along its yaw, across).
fn local(cp: &Checkpoint, p: [f64; 2]) -> (f64, f64) {
    let [c, s] = cp.axis;
    let dx = p[0] - cp.center[0];
    let dy = p[1] - cp.center[1];
    (c * dx + s * dy, -s * dx + c * dy)
}

impl CrossingTracker {
    /// A tracker that has not seen the sensor yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Places the sensor without reporting anything (after a reset or a teleport).
    pub fn place(&mut self, checkpoints: &[Checkpoint], sensor: [f64; 2]) {
        self.on_code = None;
        self.previous = Some(sensor);
        self.quiet = None;
        for (i, cp) in checkpoints.iter().enumerate() {
            let (u, v) = local(cp, sensor);
            if u.abs() <= cp.length / 2.0 && v.abs() <= cp.width / 2.0 {
                // Already on a code: it cannot count as crossed from its start.
                self.on_code = Some((i, 0));
            }
        }
    }

    /// Moves the sensor to `sensor`; returns a crossing if one completed.
    pub fn update(
        &mut self,
        checkpoints: &[Checkpoint],
        sensor: [f64; 2],
        step: u64,
    ) -> Option<Crossing> {
        let mut done = None;
        let previous = self.previous.replace(sensor);
        if let (None, Some((centre, radius))) = (self.on_code, self.quiet) {
            let (dx, dy) = (sensor[0] - centre[0], sensor[1] - centre[1]);
            if dx * dx + dy * dy < radius * radius {
                return None;
            }
        }
        // The distance to the nearest code's disc, for the next quiet disc.
        let mut room = f64::INFINITY;
        for (i, cp) in checkpoints.iter().enumerate() {
            let current = matches!(self.on_code, Some((k, _)) if k == i);
            let beyond = beyond_reach(cp, sensor);
            // Most codes are far away: nothing to follow there.
            if !current && beyond > QUIET_MARGIN {
                room = room.min(beyond);
                continue;
            }
            room = 0.0;
            let (u, v) = local(cp, sensor);
            let inside = u.abs() <= cp.length / 2.0 && v.abs() <= cp.width / 2.0;
            match self.on_code {
                Some((k, entry)) if k == i => {
                    if !inside {
                        let exit: i8 = if u >= 0.0 { 1 } else { -1 };
                        if entry != 0 && exit == -entry {
                            done = Some(Crossing {
                                checkpoint: cp.id,
                                forward: entry < 0,
                                step,
                            });
                        }
                        self.on_code = None;
                    }
                }
                _ => {
                    if inside && self.on_code.is_none() {
                        let before = previous.map_or(0.0, |p| local(cp, p).0);
                        let entry: i8 = if before >= 0.0 { 1 } else { -1 };
                        self.on_code = Some((i, entry));
                    }
                }
            }
        }
        // A margin far above rounding keeps the disc clear of every code.
        self.quiet = (self.on_code.is_none() && room > QUIET_MARGIN)
            .then_some((sensor, room - QUIET_MARGIN));
        done
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checkpoint() -> Checkpoint {
        Checkpoint {
            id: 4,
            code: vec![true, false, true, true, false],
            center: [1.0, 0.0],
            yaw: 0.0,
            width: 0.2,
            length: 0.085,
            axis: [1.0, 0.0],
        }
    }

    fn drive(from: [f64; 2], to: [f64; 2], steps: u64) -> Vec<Crossing> {
        let cps = [checkpoint()];
        let mut t = CrossingTracker::new();
        t.place(&cps, from);
        (1..=steps)
            .filter_map(|k| {
                let a = k as f64 / steps as f64;
                let p = [
                    from[0] + a * (to[0] - from[0]),
                    from[1] + a * (to[1] - from[1]),
                ];
                t.update(&cps, p, k)
            })
            .collect()
    }

    #[test]
    fn crossing_forward_and_back() {
        let fwd = drive([0.8, 0.0], [1.2, 0.05], 100);
        assert_eq!(fwd.len(), 1);
        assert!(fwd[0].forward && fwd[0].checkpoint == 4 && fwd[0].signed_id() == 4);
        let back = drive([1.2, 0.0], [0.8, 0.0], 100);
        assert_eq!(back.len(), 1);
        assert_eq!(back[0].signed_id(), -4);
    }

    #[test]
    fn turning_back_on_the_code_is_no_crossing() {
        let cps = [checkpoint()];
        let mut t = CrossingTracker::new();
        t.place(&cps, [0.9, 0.0]);
        assert!(t.update(&cps, [0.99, 0.0], 1).is_none());
        assert!(t.update(&cps, [0.9, 0.0], 2).is_none());
    }

    /// The tracker's rule looked at every code every step, as a reference.
    fn reference(cps: &[Checkpoint], path: &[[f64; 2]]) -> Vec<Crossing> {
        let mut along: Vec<f64> = cps.iter().map(|cp| local(cp, path[0]).0).collect();
        let mut on: Option<(usize, i8)> = None;
        let mut found = Vec::new();
        for (k, &p) in path.iter().enumerate().skip(1) {
            for (i, cp) in cps.iter().enumerate() {
                let (u, v) = local(cp, p);
                let inside = u.abs() <= cp.length / 2.0 && v.abs() <= cp.width / 2.0;
                match on {
                    Some((j, entry)) if j == i => {
                        if !inside {
                            let exit = if u >= 0.0 { 1 } else { -1 };
                            if exit == -entry {
                                found.push(Crossing {
                                    checkpoint: cp.id,
                                    forward: entry < 0,
                                    step: k as u64,
                                });
                            }
                            on = None;
                        }
                    }
                    _ => {
                        if inside && on.is_none() {
                            on = Some((i, if along[i] >= 0.0 { 1 } else { -1 }));
                        }
                    }
                }
                along[i] = u;
            }
        }
        found
    }

    #[test]
    fn skipping_far_codes_changes_nothing() {
        let mut second = checkpoint();
        second.id = 9;
        second.center = [1.0, 0.5];
        second.yaw = std::f64::consts::FRAC_PI_2;
        second.axis = [0.0, 1.0];
        let cps = [checkpoint(), second];
        // A wandering path (a fixed pseudo-random walk) that passes the codes many times.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut heading = 0.0_f64;
        let mut p = [0.7, 0.1];
        let mut path = vec![p];
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            heading += ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.6;
            p = [p[0] + 0.004 * heading.cos(), p[1] + 0.004 * heading.sin()];
            // Stay in a box around both codes.
            if !(0.6..=1.4).contains(&p[0]) || !(-0.3..=0.8).contains(&p[1]) {
                heading += std::f64::consts::PI;
                p = *path.last().unwrap();
            }
            path.push(p);
        }
        let expected = reference(&cps, &path);
        assert!(expected.len() > 20, "{}", expected.len());
        assert!(expected.iter().any(|c| c.checkpoint == 9));
        let mut t = CrossingTracker::new();
        t.place(&cps, path[0]);
        let found: Vec<_> = (1..path.len())
            .filter_map(|k| t.update(&cps, path[k], k as u64))
            .collect();
        assert_eq!(found, expected);
    }

    #[test]
    fn passing_beside_the_code_is_no_crossing() {
        assert!(drive([0.8, 0.3], [1.2, 0.3], 100).is_empty());
    }
}
