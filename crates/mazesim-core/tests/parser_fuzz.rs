//! Fuzzing the world TOML reader and the snapshot reader with mutated real inputs (the built-in
//! worlds, snapshots of a simulator in motion): never a panic, never a hang, every error one of
//! the reader's own kinds, and whatever is accepted is usable (a world builds a simulator; a
//! restored simulator steps on with finite poses). 256 cases each unless `PROPTEST_CASES` asks for
//! more (`make fuzz`).

use std::time::{Duration, Instant};

use mazesim_core::{Error, SimConfig, Simulator, World};
use proptest::prelude::*;
use proptest::sample::Index;

mod mutate;
use mutate::{apply, mutation};

/// Time one mutated input may take to read (debug build, slow machine).
const TIME_LIMIT: Duration = Duration::from_secs(5);

/// Pieces of TOML that stress the world reader when spliced in anywhere.
const TOML_SNIPPETS: &[&str] = &[
    "[[walls]]\n",
    "[[checkpoints]]\n",
    "[[bodies]]\n",
    "[goal]\n",
    "[start]\n",
    "center = [1e300, -1e300]\n",
    "size = [0.0, -1.0]\n",
    "yaw = nan\n",
    "radius = inf\n",
    "x = -inf\n",
    "= ",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "'''",
    "\n",
    "#",
    ",",
    "version = 99\n",
    "format = \"other\"\n",
    "9223372036854775807",
    "-9223372036854775808",
    "1e999",
    "a = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]\n",
    "b = {c = {d = {e = {f = {g = {h = {}}}}}}}\n",
    "\u{0}",
    "\u{feff}",
    "\r",
    "é",
];

/// Pieces spliced into snapshots: runs of zeros and of high bytes, text.
const SNAPSHOT_SNIPPETS: &[&str] = &[
    "\0\0\0\0\0\0\0\0",
    "\u{7f}\u{7f}\u{7f}\u{7f}",
    "mazesim",
    "\u{ffff}",
];

/// The built-in worlds' texts.
fn worlds() -> Vec<(String, Vec<u8>)> {
    mazesim_core::builtin_world_names()
        .into_iter()
        .map(|name| {
            let text = World::builtin(&name).unwrap().to_toml().unwrap();
            (name, text.into_bytes())
        })
        .collect()
}

/// Reads a world text; checks the error or that the world builds a simulator, and the time.
fn check_world(bytes: &[u8], source: &str) {
    let started = Instant::now();
    let text = String::from_utf8_lossy(bytes);
    match World::from_toml(&text, source) {
        Ok(world) => {
            let world = std::sync::Arc::new(world);
            let robot = std::sync::Arc::new(mazesim_core::RobotProfile::builtin("e-puck").unwrap());
            // A world the reader accepts either builds a simulator or is refused with a reason.
            if let Err(e) = Simulator::new(world, robot, SimConfig::default()) {
                assert!(
                    matches!(e, Error::InvalidArgument(_) | Error::Format { .. }),
                    "{e:?}"
                );
            }
        }
        Err(Error::Format { location, .. }) => assert_eq!(location.source, source),
        Err(Error::InvalidArgument(_) | Error::UnknownName { .. }) => {}
        Err(other) => panic!("expected a format error, found {other:?}"),
    }
    let took = started.elapsed();
    assert!(took < TIME_LIMIT, "{source}: took {took:?}");
}

/// A simulator in seed-maze after some steps, and its snapshot.
fn moving() -> (Simulator, Vec<u8>) {
    let world = std::sync::Arc::new(World::builtin("seed-maze").unwrap());
    let robot = std::sync::Arc::new(mazesim_core::RobotProfile::builtin("e-puck").unwrap());
    let mut sim = Simulator::new(world, robot, SimConfig::default()).unwrap();
    for k in 0..20 {
        sim.step(3.0, 2.0 + f64::from(k) * 0.1).unwrap();
    }
    let bytes = sim.snapshot();
    (sim, bytes)
}

/// Restores mutated bytes; checks the error, or that the simulator steps on with finite poses.
fn check_snapshot(sim: &mut Simulator, bytes: &[u8]) {
    let before = sim.snapshot();
    match sim.restore(bytes) {
        Ok(()) => {
            for _ in 0..3 {
                sim.step(1.0, -1.0).unwrap();
                assert!(sim.pose().iter().all(|v| v.is_finite()), "{:?}", sim.pose());
            }
        }
        Err(Error::Snapshot(_) | Error::InvalidArgument(_)) => {
            assert_eq!(
                sim.snapshot(),
                before,
                "a refused snapshot changed the simulator"
            );
        }
        Err(other) => panic!("expected a snapshot error, found {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(256),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_builtin_worlds_never_panic_or_hang(
        file in any::<Index>(),
        mutations in prop::collection::vec(mutation(TOML_SNIPPETS.len()), 1..8),
    ) {
        let corpus = worlds();
        let (name, original) = &corpus[file.index(corpus.len())];
        let mut bytes = original.clone();
        for m in &mutations {
            apply(&mut bytes, m, TOML_SNIPPETS);
        }
        check_world(&bytes, name);
    }

    #[test]
    fn mutated_snapshots_are_refused_or_restore_a_usable_state(
        mutations in prop::collection::vec(mutation(SNAPSHOT_SNIPPETS.len()), 1..6),
    ) {
        let (mut sim, original) = moving();
        let mut bytes = original.clone();
        for m in &mutations {
            apply(&mut bytes, m, SNAPSHOT_SNIPPETS);
        }
        check_snapshot(&mut sim, &bytes);
    }
}

#[test]
fn deeply_nested_toml_is_a_format_error() {
    for depth in [1_000, 100_000] {
        let text = format!("a = {}{}\n", "[".repeat(depth), "]".repeat(depth));
        check_world(text.as_bytes(), "nested.toml");
        let text = format!("a = {}{}\n", "{b = ".repeat(depth), "}".repeat(depth));
        check_world(text.as_bytes(), "nested.toml");
    }
}
