//! Ground truth of barcode crossings: which checkpoint's code the barcode sensor actually crossed,
//! in which direction, and when. A crossing is complete when the sensor leaves a code on the
//! opposite end from where it came in; leaving on the same end (turning back on the code) is not
//! a crossing.

use crate::world::Checkpoint;

/// Metres kept between a watch disc and the discs of the codes it does not watch: far above
/// rounding, so that no code the sensor may be on goes unwatched.
const WATCH_MARGIN: f64 = 1e-6;

/// Codes whose disc comes within this many metres of the sensor are watched from there on; the
/// others are left alone until it has moved about as far.
const WATCH_REACH: f64 = 0.05;

/// One completed crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CrossingTracker {
    /// The code the sensor is on (index into the world's checkpoints) and the end it came in by
    /// (-1 = the start of the code, +1 = its end).
    on_code: Option<(usize, i8)>,
    /// The sensor's position at the last update or placement, to know the end by which it came
    /// onto a code.
    previous: Option<[f64; 2]>,
    /// A disc (centre, radius) that reaches the discs of the `watched` codes only: while the
    /// sensor stays in it, it can be on no other code, and the others need not be looked at.
    watch: Option<([f64; 2], f64)>,
    /// Indices of the codes the watch disc reaches (and of the code the sensor is on), in order.
    watched: Vec<usize>,
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

    /// Bytes of its buffers on the heap (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        crate::footprint::vec_bytes(&self.watched)
    }

    /// Whether every code index it holds is below `codes` and its positions are finite: what a
    /// tracker read back from a snapshot must satisfy to follow a world of `codes` checkpoints.
    pub fn fits(&self, codes: usize) -> bool {
        let finite = |p: &[f64]| p.iter().all(|v| v.is_finite());
        self.on_code
            .is_none_or(|(i, end)| i < codes && (-1..=1).contains(&end))
            && self.previous.is_none_or(|p| finite(&p))
            && self.watch.is_none_or(|(c, r)| finite(&c) && !r.is_nan())
            && self.watched.iter().all(|&i| i < codes)
    }

    /// Places the sensor without reporting anything (after a reset or a teleport).
    pub fn place(&mut self, checkpoints: &[Checkpoint], sensor: [f64; 2]) {
        self.on_code = None;
        self.previous = Some(sensor);
        self.watch = None;
        for (i, cp) in checkpoints.iter().enumerate() {
            let (u, v) = local(cp, sensor);
            if u.abs() <= cp.length / 2.0 && v.abs() <= cp.width / 2.0 {
                // Already on a code: it cannot count as crossed from its start.
                self.on_code = Some((i, 0));
            }
        }
    }

    /// Moves the sensor to `sensor`; returns a crossing if one completed. `checkpoints` are those
    /// of the last `place`.
    pub fn update(
        &mut self,
        checkpoints: &[Checkpoint],
        sensor: [f64; 2],
        step: u64,
    ) -> Option<Crossing> {
        let mut done = None;
        let previous = self.previous.replace(sensor);
        let watching = self.watch.is_some_and(|(centre, radius)| {
            let (dx, dy) = (sensor[0] - centre[0], sensor[1] - centre[1]);
            dx * dx + dy * dy < radius * radius
        });
        if !watching {
            self.watch_around(checkpoints, sensor);
        }
        // The sensor is on no other code than these: on the others, nothing can happen.
        for &i in &self.watched {
            let cp = &checkpoints[i];
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
        done
    }

    /// Watches the codes within `WATCH_REACH` of `sensor` (and the one it is on), over a disc
    /// around it that keeps `WATCH_MARGIN` from the discs of all the others.
    fn watch_around(&mut self, checkpoints: &[Checkpoint], sensor: [f64; 2]) {
        self.watched.clear();
        // The distance to the nearest unwatched code's disc.
        let mut room = f64::INFINITY;
        for (i, cp) in checkpoints.iter().enumerate() {
            let current = matches!(self.on_code, Some((k, _)) if k == i);
            let beyond = beyond_reach(cp, sensor);
            if current || beyond <= WATCH_REACH {
                self.watched.push(i);
            } else {
                room = room.min(beyond);
            }
        }
        self.watch = Some((sensor, room - WATCH_MARGIN));
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

    #[test]
    fn watching_the_near_codes_only_changes_nothing() {
        // Three junctions with a code on each way in, as the maze generator lays them out:
        // the codes' discs overlap, and the sensor is near one most of the time.
        let mut cps = Vec::new();
        for junction in [[0.125, 0.125], [0.625, 0.375], [0.375, 0.875]] {
            for d in 0..4 {
                let out = d as f64 * std::f64::consts::FRAC_PI_2;
                let mut cp = checkpoint();
                cp.id = cps.len() as u32 + 1;
                cp.center = [
                    junction[0] + 0.125 * out.cos(),
                    junction[1] + 0.125 * out.sin(),
                ];
                cp.yaw = out + std::f64::consts::PI;
                cp.axis = [cp.yaw.cos(), cp.yaw.sin()];
                cp.width = 0.23;
                cps.push(cp);
            }
        }
        let on_a_code = |p: [f64; 2]| {
            cps.iter().any(|cp| {
                let (u, v) = local(cp, p);
                u.abs() <= cp.length / 2.0 && v.abs() <= cp.width / 2.0
            })
        };
        let mut rng = crate::rng::Rng::new(0x9e37_79b9_7f4a_7c15);
        let mut uniform = move || rng.uniform();
        let mut t = CrossingTracker::new();
        let mut total = 0;
        for _ in 0..40 {
            // Walks start off the codes: the reference knows nothing of a start on one.
            let mut p = [uniform() * 1.0 - 0.1, uniform() * 1.2 - 0.1];
            while on_a_code(p) {
                p = [uniform() * 1.0 - 0.1, uniform() * 1.2 - 0.1];
            }
            let mut heading = uniform() * 6.3;
            let mut path = vec![p];
            for _ in 0..5_000 {
                heading += (uniform() - 0.5) * 0.5;
                let next = [p[0] + 0.004 * heading.cos(), p[1] + 0.004 * heading.sin()];
                if !(-0.2..=1.0).contains(&next[0]) || !(-0.2..=1.2).contains(&next[1]) {
                    heading += std::f64::consts::PI;
                } else {
                    p = next;
                }
                path.push(p);
            }
            let expected = reference(&cps, &path);
            t.place(&cps, path[0]);
            let found: Vec<_> = (1..path.len())
                .filter_map(|k| t.update(&cps, path[k], k as u64))
                .collect();
            assert_eq!(found, expected);
            total += found.len();
        }
        assert!(total > 300, "{total}");
    }
}
