//! Ground truth of barcode crossings: which checkpoint's code the barcode sensor actually crossed,
//! in which direction, and when. A crossing is complete when the sensor leaves a code on the
//! opposite end from where it came in; leaving on the same end (turning back on the code) is not
//! a crossing.

use crate::world::Checkpoint;

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
    /// Position along the last code's axis before entering, to know the end it came in by.
    last_along: Vec<f64>,
}

/// Where `p` lies in a checkpoint's frame: (along its yaw, across).
fn local(cp: &Checkpoint, p: [f64; 2]) -> (f64, f64) {
    let [c, s] = cp.axis;
    let dx = p[0] - cp.center[0];
    let dy = p[1] - cp.center[1];
    (c * dx + s * dy, -s * dx + c * dy)
}

impl CrossingTracker {
    /// A tracker for a world with `n` checkpoints.
    pub fn new(n: usize) -> Self {
        Self {
            on_code: None,
            last_along: vec![0.0; n],
        }
    }

    /// Places the sensor without reporting anything (after a reset or a teleport).
    pub fn place(&mut self, checkpoints: &[Checkpoint], sensor: [f64; 2]) {
        self.on_code = None;
        for (i, cp) in checkpoints.iter().enumerate() {
            let (u, v) = local(cp, sensor);
            self.last_along[i] = u;
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
        for (i, cp) in checkpoints.iter().enumerate() {
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
                        let before = self.last_along[i];
                        let entry: i8 = if before >= 0.0 { 1 } else { -1 };
                        self.on_code = Some((i, entry));
                    }
                }
            }
            self.last_along[i] = u;
        }
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
        let mut t = CrossingTracker::new(1);
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
        let mut t = CrossingTracker::new(1);
        t.place(&cps, [0.9, 0.0]);
        assert!(t.update(&cps, [0.99, 0.0], 1).is_none());
        assert!(t.update(&cps, [0.9, 0.0], 2).is_none());
    }

    #[test]
    fn passing_beside_the_code_is_no_crossing() {
        assert!(drive([0.8, 0.3], [1.2, 0.3], 100).is_empty());
    }
}
