//! The door sub-tasks' odometry replays, bit for bit, what the oracle `SubTaskTracker` in `tests/navigator_oracle.py`
//! did on the same poses (`tests/data/door_subtasks.txt`, written and checked against the
//! tracker by `tests/learn/test_door_odometry.py`): the phase, the end and the heading change of
//! every step.

use mazesim_core::navigator::door::{SubTaskEnd, SubTaskState};

fn pose(fields: &[&str]) -> [f32; 3] {
    [0, 1, 2].map(|i| f32::from_bits(fields[i].parse().unwrap()))
}

#[test]
fn the_core_follows_the_tracker_bit_for_bit() {
    let text = include_str!("data/door_subtasks.txt");
    let mut ends = [0usize; 3];
    let mut sequences = 0;
    for sequence in text.split("\n\n").filter(|s| !s.trim().is_empty()) {
        let mut lines = sequence.lines();
        let head: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
        let mut task = SubTaskState::begin(head[0].parse().unwrap(), pose(&head[1..]));
        for (step, line) in lines.enumerate() {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let end = task.update(pose(&fields));
            let expected_end = match fields[4] {
                "0" => SubTaskEnd::Running,
                "1" => SubTaskEnd::Done,
                _ => SubTaskEnd::GaveUp,
            };
            let at = format!("sequence {sequences}, step {step}");
            assert_eq!(
                task.phase,
                fields[3].parse::<usize>().unwrap(),
                "phase, {at}"
            );
            assert_eq!(end, expected_end, "end, {at}");
            let change: u64 = fields[5].parse().unwrap();
            assert_eq!(
                task.heading_change.to_bits(),
                change,
                "heading change, {at}"
            );
            ends[fields[4].parse::<usize>().unwrap()] += 1;
        }
        sequences += 1;
    }
    assert_eq!(sequences, 60);
    assert!(ends.iter().all(|&count| count > 0), "{ends:?}");
}
