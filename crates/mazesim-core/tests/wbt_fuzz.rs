//! Fuzzing the `.wbt` reader and importer with mutated real worlds (byte flips, truncations,
//! insertions of syntax, deletions, duplications): never a panic, never a hang, and every error
//! is a format error with a line and a column inside the text.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use mazesim_core::wbt::WbtImport;
use mazesim_core::Error;
use proptest::prelude::*;
use proptest::sample::Index;

mod mutate;
use mutate::{apply, mutation};

/// Time one mutated file may take to read, import and build (debug build, slow machine).
const TIME_LIMIT: Duration = Duration::from_secs(5);

/// Pieces of syntax that stress the reader when spliced in anywhere.
const SNIPPETS: &[&str] = &[
    "{",
    "}",
    "[",
    "]",
    "\"",
    "#",
    "\n",
    ",",
    "DEF A ",
    "USE A ",
    "USE WALL_SHAPE ",
    "USE W008 ",
    "NULL ",
    "hidden ",
    "hidden rotation_1 0 1 0 ",
    "TRUE ",
    "IS x ",
    "1e999 ",
    "-",
    "0x",
    ".",
    "-.e5 ",
    "PROTO P [ ] { } ",
    "EXTERNPROTO ",
    "ROUTE a.b TO c.d\n",
    "Solid { boundingObject Box { size 1 1 1 } } ",
    "Transform { scale 0 0 0 children [ ",
    "Pose { rotation 0 0 0 1 children [ Box { } ] } ",
    "E-puck { rotation 1 0 0 1 } ",
    "WorldInfo { coordinateSystem \"NUE\" basicTimeStep 0 } ",
    "Cylinder { radius -1 } ",
    "translation 1e300 1e300 0 ",
    "size 0 0 0 ",
    "\u{0}",
    "\u{feff}",
    "é",
    "\u{1F600}",
];

fn corpus() -> Vec<(String, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/webots-worlds");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| {
            panic!(
                "the Webots test corpus is missing at {}: {e}",
                dir.display()
            )
        })
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "wbt"))
        .collect();
    files.sort();
    assert_eq!(
        files.len(),
        6,
        "expected the six corpus worlds in {}",
        dir.display()
    );
    files
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read(&p).unwrap()))
        .collect()
}

/// Reads, imports and builds; checks the error or the result, and the time taken.
fn check(bytes: &[u8], source: &str) {
    let started = Instant::now();
    match WbtImport::from_bytes(bytes, source) {
        Ok(import) => {
            for obstacle in &import.obstacles {
                let text = format!("{obstacle:?}");
                assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
            }
            assert!(import.basic_time_step_ms > 0.0);
            import
                .to_world("fuzz")
                .unwrap_or_else(|e| panic!("an import that succeeded must build a world: {e}"));
        }
        Err(Error::Format { location, .. }) => {
            // Lines end as the reader ends them: at a line feed, or at a lone carriage return
            // (the line ends of classic Mac OS files).
            let ends = bytes
                .iter()
                .enumerate()
                .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')));
            let lines = ends.count() + 1;
            assert_eq!(location.source, source);
            assert!(
                location.line >= 1 && location.line <= lines,
                "line {} of {lines}",
                location.line
            );
            assert!(location.column >= 1, "column {}", location.column);
        }
        Err(other) => panic!("expected a format error, found {other:?}"),
    }
    let took = started.elapsed();
    assert!(took < TIME_LIMIT, "{source}: took {took:?}");
}

proptest! {
    // 512 cases unless PROPTEST_CASES asks for another number (a longer fuzzing run).
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(512),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_real_worlds_never_panic_or_hang(
        file in any::<Index>(),
        mutations in prop::collection::vec(mutation(SNIPPETS.len()), 1..8),
    ) {
        let corpus = corpus();
        let (name, original) = &corpus[file.index(corpus.len())];
        let mut bytes = original.clone();
        for m in &mutations {
            apply(&mut bytes, m, SNIPPETS);
        }
        check(&bytes, name);
    }
}

#[test]
fn every_truncation_of_every_world_is_handled() {
    for (name, bytes) in corpus() {
        for end in 0..=bytes.len() {
            check(&bytes[..end], &name);
        }
    }
}

#[test]
fn malformed_input_names_line_and_column() {
    let cases: &[(&str, usize, usize)] = &[
        (
            "#VRML_SIM R2023b utf8\nSolid {\n  translation 1 2 3\n",
            4,
            1,
        ),
        (
            "#VRML_SIM R2023b utf8\nSolid { translation 1 2 3 } ]\n",
            2,
            29,
        ),
        // A translation short of a number is refused where its third number should be.
        (
            "#VRML_SIM R2023b utf8\nSolid { translation 1 2 } ]\n",
            2,
            25,
        ),
        ("#VRML_SIM R2023b utf8\nSolid { name \"open\n", 2, 14),
        ("#VRML_SIM R2023b utf8\nSolid { size 1..2 }\n", 2, 14),
        ("#VRML_SIM R2023b utf8\n  Box size 1 }\n", 2, 7),
        ("not a world\n", 1, 1),
        ("#VRML_SIM R20x3b utf8\n", 1, 11),
    ];
    for &(text, line, column) in cases {
        match WbtImport::from_text(text, "bad.wbt") {
            Err(Error::Format { location, .. }) => {
                assert_eq!((location.line, location.column), (line, column), "{text:?}");
            }
            other => panic!("expected a format error for {text:?}, found {other:?}"),
        }
    }
}
