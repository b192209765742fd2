//! Tabular Q-learning updates, one batch of transitions at a time (`mazesim.learn.qlearning`).
//!
//! A table holds `rows x actions` values, row-major, with the count of updates of each pair beside
//! it. One update of the transition `(s, a, r, s')` is
//!
//! ```text
//! Q[s, a] <- Q[s, a] + alpha * (r + bootstrap * max_b Q[s', b] - Q[s, a])
//! ```
//!
//! where the max runs over the table's allowed actions, `bootstrap` is 0 at the end of an episode
//! (`s'` is then never read) and `alpha` is the pair's learning rate after its earlier updates
//! ([`LearningRate`]). A batch is N transitions of environments stepped together: their targets
//! read the table as it was before the batch, then the updates apply one after the other in the
//! batch's order, so k transitions of one pair move it k times, each by its own rate.

use crate::error::{Error, Result};

/// The learning rate of a pair's n-th update (n = 0, 1, ...):
/// `max(floor, initial * (n + 1) ^ -power)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LearningRate {
    /// The rate of a pair's first update.
    pub initial: f64,
    /// The rate never falls below this.
    pub floor: f64,
    /// How fast the rate falls with the count of updates.
    pub power: f64,
}

impl LearningRate {
    /// Checks `0 < floor <= initial <= 0.5` and `power >= 0`.
    pub fn new(initial: f64, floor: f64, power: f64) -> Result<Self> {
        if !(0.0 < floor && floor <= initial && initial <= 0.5 && power >= 0.0) {
            return Err(Error::InvalidArgument(format!(
                "expected 0 < floor <= initial <= 0.5 and power >= 0, found initial={initial}, \
                 floor={floor}, power={power}"
            )));
        }
        Ok(Self {
            initial,
            floor,
            power,
        })
    }

    /// The rate of the update that follows `visits` earlier updates of a pair.
    pub fn after(&self, visits: i64) -> f64 {
        let rate = self.initial * (visits as f64 + 1.0).powf(-self.power);
        rate.max(self.floor)
    }
}

/// The greedy action of one row of values among the `allowed` action indices (listed in
/// increasing order): the largest, ties going to the lowest index (0 when none is allowed).
pub fn best_action(values: &[f64], allowed: impl IntoIterator<Item = usize>) -> usize {
    let mut best: Option<usize> = None;
    for action in allowed {
        if best.is_none_or(|b| values[action] > values[b]) {
            best = Some(action);
        }
    }
    best.unwrap_or(0)
}

/// One transition of a batch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition {
    /// The row the action was taken in.
    pub state: usize,
    /// The action taken.
    pub action: usize,
    /// The reward received (discounted along the way for a decision of several steps).
    pub reward: f64,
    /// The row reached (not read when `bootstrap` is 0).
    pub next_state: usize,
    /// The factor of `max Q[s']`: `gamma ^ tau`, or 0 at the end of an episode.
    pub bootstrap: f64,
}

/// One Q-table of `actions` columns and the update counts of its pairs, both row-major.
pub struct QTable<'a> {
    /// The values.
    pub values: &'a mut [f64],
    /// The update count of each pair.
    pub visits: &'a mut [i64],
    /// Columns per row.
    pub actions: usize,
}

impl QTable<'_> {
    /// Rows of the table.
    pub fn rows(&self) -> usize {
        self.values.len() / self.actions.max(1)
    }

    /// The greedy action of `row` among the `allowed` ones (see [`best_action`]).
    pub fn best(&self, row: usize, allowed: &[bool]) -> usize {
        let values = &self.values[row * self.actions..(row + 1) * self.actions];
        best_action(values, (0..self.actions).filter(|&a| allowed[a]))
    }

    /// The largest allowed value of `row`.
    fn best_value(&self, row: usize, allowed: &[bool]) -> f64 {
        let values = &self.values[row * self.actions..(row + 1) * self.actions];
        values
            .iter()
            .zip(allowed)
            .filter(|(_, &ok)| ok)
            .map(|(&v, _)| v)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Applies a batch of transitions in place, as the module says; `targets` is scratch space.
    /// Every index must be in the table (see [`QTable::check`]).
    pub fn update(
        &mut self,
        batch: &[Transition],
        allowed: &[bool],
        rate: &LearningRate,
        targets: &mut Vec<f64>,
    ) {
        targets.clear();
        // Each pair's value and count are read here too, where the loads do not wait on one
        // another, so that the updates below, one after the other, find them in cache.
        let mut touched = 0;
        targets.extend(batch.iter().map(|t| {
            let pair = t.state * self.actions + t.action;
            touched ^= self.values[pair].to_bits() ^ self.visits[pair] as u64;
            let best = if t.bootstrap != 0.0 {
                self.best_value(t.next_state, allowed)
            } else {
                0.0
            };
            t.reward + t.bootstrap * best
        }));
        std::hint::black_box(touched);
        for (t, &target) in batch.iter().zip(targets.iter()) {
            let pair = t.state * self.actions + t.action;
            let alpha = rate.after(self.visits[pair]);
            self.values[pair] += alpha * (target - self.values[pair]);
            self.visits[pair] += 1;
        }
    }

    /// Checks the table's shape against its counts and every transition's indices and numbers
    /// (the next state only where it is read: `bootstrap` not 0).
    pub fn check(&self, batch: &[Transition], allowed: &[bool]) -> Result<()> {
        let rows = self.rows();
        if self.actions == 0
            || self.values.len() != rows * self.actions
            || self.visits.len() != self.values.len()
        {
            return Err(Error::InvalidArgument(format!(
                "expected a Q-table and visit counts of one shape (rows, {}), found {} values and \
                 {} counts",
                self.actions,
                self.values.len(),
                self.visits.len()
            )));
        }
        if let Some(at) = self.visits.iter().position(|&v| v < 0) {
            return Err(Error::InvalidArgument(format!(
                "expected visit counts of 0 or more, found {} at state {}, action {}",
                self.visits[at],
                at / self.actions,
                at % self.actions
            )));
        }
        if allowed.len() != self.actions || !allowed.iter().any(|&ok| ok) {
            return Err(Error::InvalidArgument(format!(
                "expected {} allowed-action flags, at least one true, found {:?}",
                self.actions, allowed
            )));
        }
        for (i, t) in batch.iter().enumerate() {
            if t.state >= rows || (t.bootstrap != 0.0 && t.next_state >= rows) {
                return Err(Error::InvalidArgument(format!(
                    "expected states in [0, {rows}), found {} -> {} at transition {i}",
                    t.state, t.next_state
                )));
            }
            if t.action >= self.actions {
                return Err(Error::InvalidArgument(format!(
                    "expected actions in [0, {}), found {} at transition {i}",
                    self.actions, t.action
                )));
            }
            if !t.reward.is_finite() || !t.bootstrap.is_finite() {
                return Err(Error::InvalidArgument(format!(
                    "expected a finite reward and bootstrap, found {} and {} at transition {i}",
                    t.reward, t.bootstrap
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rate() -> LearningRate {
        LearningRate::new(0.5, 0.02, 0.5).unwrap()
    }

    #[test]
    fn the_rate_falls_with_the_updates_down_to_its_floor() {
        let r = rate();
        assert_eq!(r.after(0), 0.5);
        assert_eq!(r.after(3), 0.25);
        assert_eq!(r.after(10_000), 0.02);
        assert!(LearningRate::new(0.6, 0.02, 0.5).is_err());
        assert!(LearningRate::new(0.5, 0.0, 0.5).is_err());
    }

    #[test]
    fn a_batch_reads_targets_before_it_and_applies_in_order() {
        let mut values = vec![0.0, 0.0, 1.0, 3.0];
        let mut visits = vec![0; 4];
        let mut table = QTable {
            values: &mut values,
            visits: &mut visits,
            actions: 2,
        };
        let allowed = [true, false];
        // Two updates of pair (0, 0) towards 1 + 0.5 * Q[1, 0] (= 1: Q[1, 1] is not allowed),
        // then one of (1, 0) ending the episode with reward 2.
        let step = |reward, bootstrap| Transition {
            state: 0,
            action: 0,
            reward,
            next_state: 1,
            bootstrap,
        };
        let end = Transition {
            state: 1,
            action: 0,
            reward: 2.0,
            next_state: 0,
            bootstrap: 0.0,
        };
        let batch = [step(0.5, 0.5), step(0.5, 0.5), end];
        table.check(&batch, &allowed).unwrap();
        table.update(&batch, &allowed, &rate(), &mut Vec::new());
        // 0 -> 0.5 (rate 0.5), then 0.5 + 0.5^0.5/2 * 0.5 with the target read before the batch.
        let second = 0.5 * 2f64.powf(-0.5);
        assert_eq!(values[0], 0.5 + second * (1.0 - 0.5));
        assert_eq!(values[2], 1.0 + 0.5 * (2.0 - 1.0));
        assert_eq!(visits, vec![2, 0, 1, 0]);
    }

    #[test]
    fn greedy_ties_go_to_the_lowest_allowed_action() {
        let mut values = vec![1.0, 1.0, 1.0, 2.0];
        let mut visits = vec![0; 4];
        let table = QTable {
            values: &mut values,
            visits: &mut visits,
            actions: 4,
        };
        assert_eq!(table.best(0, &[true; 4]), 3);
        assert_eq!(table.best(0, &[true, true, true, false]), 0);
        assert_eq!(table.best(0, &[false, true, true, false]), 1);
    }

    #[test]
    fn bad_transitions_are_refused() {
        let mut values = vec![0.0; 4];
        let mut visits = vec![0; 4];
        let table = QTable {
            values: &mut values,
            visits: &mut visits,
            actions: 2,
        };
        let bad = Transition {
            state: 2,
            action: 0,
            reward: 0.0,
            next_state: 0,
            bootstrap: 0.0,
        };
        let err = table.check(&[bad], &[true, true]).unwrap_err().to_string();
        assert!(err.contains("[0, 2)"), "{err}");
        let nan = Transition {
            state: 0,
            reward: f64::NAN,
            ..bad
        };
        assert!(table.check(&[nan], &[true, true]).is_err());
        let mut negative = [0, 0, -3, 0];
        let counted = QTable {
            values: &mut [0.0; 4],
            visits: &mut negative,
            actions: 2,
        };
        let err = counted.check(&[], &[true, true]).unwrap_err().to_string();
        assert!(err.contains("-3 at state 1, action 0"), "{err}");
        assert!(table.check(&[], &[false, false]).is_err());
    }
}
