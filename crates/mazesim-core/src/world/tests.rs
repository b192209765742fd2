//! World files: round trips, located errors, built-in worlds.

use super::*;
use proptest::prelude::*;

const HEADER: &str = "format = \"mazesim-world\"\nversion = 1\n";

fn parse(body: &str) -> Result<World> {
    World::from_toml(&format!("{HEADER}{body}"), "bad.toml")
}

fn format_error(body: &str) -> (usize, String, String) {
    match parse(body) {
        Err(Error::Format {
            location,
            field,
            message,
        }) => {
            assert_eq!(location.source, "bad.toml");
            (location.line, field, message)
        }
        other => panic!("expected a format error, found {other:?}"),
    }
}

#[test]
fn builtin_worlds_load_and_round_trip() {
    for name in builtin_world_names() {
        let w = World::builtin(&name).unwrap();
        let again = World::from_toml(&w.to_toml().unwrap(), "again").unwrap();
        assert_eq!(w, again, "{name}");
        assert_eq!(w.walls(), again.walls());
        assert_eq!(w.floor(), again.floor());
    }
    let seed = World::builtin("seed-maze").unwrap();
    assert_eq!(seed.checkpoints().len(), 7);
    assert!(seed.goal().is_some());
    assert!(seed.maze().is_some());
}

#[test]
fn unknown_builtin_lists_the_available_ones() {
    let err = World::builtin("maze-of-doom").unwrap_err().to_string();
    for name in ["seed-maze", "line-follow", "arena"] {
        assert!(err.contains(name), "{err}");
    }
}

#[test]
fn a_bad_value_names_line_and_field() {
    let (line, field, message) = format_error("[[walls]]\ncenter = [0, 0]\nsize = [0.1, 0.1]\n[[walls]]\ncenter = [1, 0]\nsize = [-0.1, 0.1]\n");
    assert_eq!(line, 8);
    assert_eq!(field, "walls[1].size");
    assert!(
        message.contains("above zero") && message.contains("-0.1"),
        "{message}"
    );
}

#[test]
fn unknown_fields_missing_fields_and_wrong_versions_are_located() {
    let (line, field, message) = format_error("[goal]\ncentre = [0, 0]\nradius = 0.1\n");
    assert_eq!((line, field.as_str()), (4, "goal.centre"));
    assert!(message.contains("centre"), "{message}");
    let (_, _, message) = format_error("[goal]\nradius = 0.1\n");
    assert!(message.contains("center"), "{message}");
    let err = World::from_toml("format = \"mazesim-world\"\nversion = 7\n", "v.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("v.toml:2") && err.contains("version") && err.contains('7'),
        "{err}"
    );
    let err = World::from_toml("format = \"webots\"\nversion = 1\n", "f.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("f.toml:1") && err.contains("mazesim-world"),
        "{err}"
    );
    let (line, _, _) = format_error("[floor]\nreflectance = 1.5\n");
    assert_eq!(line, 4);
}

#[test]
fn a_world_without_its_header_names_the_lines_to_write() {
    for text in [
        "[[walls]]\ncenter = [0, 0]\nsize = [1, 1]\n",
        "version = 1\n[goal]\ncenter = [0, 0]\nradius = 0.1\n",
        "format = \"mazesim-world\"\n",
    ] {
        let err = World::from_toml(text, "h.toml").unwrap_err();
        let Error::Format { field, message, .. } = &err else {
            panic!("{err}");
        };
        assert_eq!(field, "(top level)", "{err}");
        assert!(
            message.contains("format = \"mazesim-world\"") && message.contains("version = 1"),
            "{err}"
        );
    }
}

#[test]
fn grid_errors_point_into_the_drawing() {
    let (line, field, message) = format_error("[grid]\ncell_size = 0.25\nwall_thickness = 0.01\nmap = \"\"\"\n+--+--+\n|  x  |\n+--+--+\n\"\"\"\n");
    assert_eq!(field, "grid.map");
    assert_eq!(line, 8, "{message}");
    assert!(message.contains("'x'"), "{message}");
}

#[test]
fn checkpoint_ids_are_positive_and_unique_and_codes_are_five_bits() {
    let cp = |id: u32, code: &str| {
        format!("[[checkpoints]]\nid = {id}\ncode = \"{code}\"\ncenter = [0, 0]\nyaw = 0\nwidth = 0.2\n")
    };
    let (line, field, message) = format_error(&format!("{}{}", cp(1, "10110"), cp(1, "11010")));
    assert_eq!((line, field.as_str()), (9, "checkpoints[1].id"));
    assert_eq!(
        message,
        "expected a unique checkpoint id, found 1 a second time"
    );
    let (line, field, message) = format_error(&format!("{}{}", cp(1, "10110"), cp(0, "11010")));
    assert_eq!((line, field.as_str()), (9, "checkpoints[1].id"));
    assert_eq!(message, "expected a positive checkpoint id, found 0");
    let (line, field, _) = format_error(&cp(3, "1011"));
    assert_eq!((line, field.as_str()), (5, "checkpoints[0].code"));
}

#[test]
fn barcode_bars_are_painted_first_bit_first_along_yaw() {
    let w = parse("[floor]\nreflectance = 0.36\n[[checkpoints]]\nid = 1\ncode = \"10010\"\ncenter = [0, 0]\nyaw = 1.5707963267948966\nwidth = 0.2\n").unwrap();
    let f = w.floor();
    let along = |t: f64| f.reflectance_at([0.0, t]);
    assert_eq!(along(-0.034), 1.0);
    assert_eq!(along(-0.017), 0.2);
    assert_eq!(along(0.0), 0.2);
    assert_eq!(along(0.017), 1.0);
    assert_eq!(along(0.034), 0.2);
    assert_eq!(along(0.06), 0.36);
}

#[test]
fn polylines_need_two_points() {
    let (_, field, message) = format_error(
        "[[paint]]\nshape = \"polyline\"\npoints = [[0, 0]]\nwidth = 0.01\nreflectance = 0.2\n",
    );
    assert_eq!(field, "paint[0].points");
    assert!(message.contains("at least 2"), "{message}");
}

#[test]
fn saving_is_atomic_and_round_trips() {
    let dir = std::env::temp_dir().join(format!("mazesim-world-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("w.toml");
    let w = World::builtin("seed-maze").unwrap();
    w.save(&path).unwrap();
    assert_eq!(World::load(&path).unwrap(), w);
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
    assert!(matches!(
        World::load(&dir.join("missing.toml")),
        Err(Error::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_world_file_without_a_name_is_named_after_the_file() {
    let dir = std::env::temp_dir().join(format!("mazesim-world-name-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let header = "format = \"mazesim-world\"\nversion = 1\n";
    let unnamed = dir.join("my-maze.toml");
    std::fs::write(&unnamed, header).unwrap();
    assert_eq!(World::load(&unnamed).unwrap().name(), "my-maze");
    let named = dir.join("file.toml");
    std::fs::write(&named, format!("{header}name = \"kept\"\n")).unwrap();
    assert_eq!(World::load(&named).unwrap().name(), "kept");
    assert_eq!(World::from_toml(header, "x.toml").unwrap().name(), "");
    std::fs::remove_dir_all(&dir).unwrap();
}

fn finite() -> impl Strategy<Value = f64> {
    -10.0f64..10.0
}
fn positive() -> impl Strategy<Value = f64> {
    0.001f64..2.0
}
fn reflectance() -> impl Strategy<Value = f64> {
    0.01f64..=1.0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_worlds_round_trip(
        walls in prop::collection::vec((finite(), finite(), positive(), positive(), finite(), reflectance()), 0..6),
        paint in prop::collection::vec((finite(), finite(), positive(), reflectance()), 0..6),
        start in (finite(), finite(), finite()),
        step in 1.0f64..64.0,
    ) {
        let mut text = format!("{HEADER}name = \"random\"\nbasic_time_step_ms = {step:?}\n[start]\nx = {:?}\ny = {:?}\nyaw = {:?}\n", start.0, start.1, start.2);
        for (x, y, sx, sy, yaw, f) in &walls {
            text += &format!("[[walls]]\ncenter = [{x:?}, {y:?}]\nsize = [{sx:?}, {sy:?}]\nyaw = {yaw:?}\nreflectance = {f:?}\n");
        }
        for (x, y, r, f) in &paint {
            text += &format!("[[paint]]\nshape = \"circle\"\ncenter = [{x:?}, {y:?}]\nradius = {r:?}\nreflectance = {f:?}\n");
        }
        let w = World::from_toml(&text, "random").unwrap();
        let again = World::from_toml(&w.to_toml().unwrap(), "again").unwrap();
        prop_assert_eq!(&w, &again);
        prop_assert_eq!(w.walls(), again.walls());
        prop_assert_eq!(w.walls().len(), walls.len());
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        let _ = World::from_toml(&text, "fuzz");
        let _ = World::from_toml(&format!("{HEADER}{text}"), "fuzz");
    }
}

#[test]
fn a_wall_a_kilometre_away_does_not_blow_up_the_index() {
    let w = parse("[[walls]]\ncenter = [0, 0]\nsize = [0.1, 0.1]\n[[walls]]\ncenter = [990, -990]\nsize = [0.1, 0.1]\n[[paint]]\nshape = \"circle\"\ncenter = [-990, 0]\nradius = 0.1\nreflectance = 0.2\n").unwrap();
    let hit = w
        .wall_index()
        .cast_ray([-1.0, 0.0], [1.0, 0.0], 2.0)
        .unwrap();
    assert!((hit.distance - 0.95).abs() < 1e-4);
    assert_eq!(w.floor().reflectance_at([-990.0, 0.0]), 0.2);
    assert_eq!(w.floor().reflectance_at([0.0, 0.0]), 1.0);
}

#[test]
fn a_wall_far_from_the_origin_is_refused_with_its_field_and_range() {
    let Err(Error::Format { field, message, .. }) =
        parse("[[walls]]\ncenter = [1e20, 0]\nsize = [0.1, 0.1]\n")
    else {
        panic!("refused")
    };
    assert_eq!(field, "walls[0]");
    assert!(
        message.contains("[-1000, 1000]") && message.contains("1e20"),
        "{message}"
    );
}

#[test]
fn coincident_walls_are_one_solid() {
    let wall = "[[walls]]\ncenter = [0.2, 0]\nsize = [0.1, 0.1]\n";
    let w = parse(&wall.repeat(30_000)).unwrap();
    assert_eq!(w.walls().len(), 30_000);
    assert_eq!(w.solid_walls().len(), 1);
}

#[test]
fn crowded_overlapping_walls_are_refused() {
    let text: String = (0..3_000)
        .map(|i| {
            format!(
                "[[walls]]\ncenter = [{}, 0]\nsize = [0.1, 0.1]\n",
                i as f64 * 1e-6
            )
        })
        .collect();
    let Err(Error::Format { field, message, .. }) = parse(&text) else {
        panic!("refused")
    };
    assert_eq!(field, "walls");
    assert!(message.contains("pairs"), "{message}");
}

/// Numbers that break careless code: beyond every limit, tiny, not finite (as TOML writes them).
fn hostile_number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-1500.0f64..1500.0).prop_map(|v| format!("{v:?}")),
        prop::sample::select(vec![
            "1e20",
            "1e39",
            "-1e300",
            "3.5e38",
            "1e-300",
            "1e5",
            "999.999",
            "nan",
            "inf",
            "-inf",
            "0.0",
            "4294967296.0",
        ])
        .prop_map(String::from),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]
    /// Issue #15: a world file of hostile numbers compiles into a world within the limits or is a
    /// format error; it never panics, and a simulator made from it keeps a finite pose.
    #[test]
    fn hostile_numbers_give_a_bounded_world_or_a_format_error(
        walls in prop::collection::vec(prop::collection::vec(hostile_number(), 5), 0..4),
        start in prop::collection::vec(hostile_number(), 3),
        step in hostile_number(),
    ) {
        let mut text = format!(
            "{HEADER}basic_time_step_ms = {step}\n[start]\nx = {}\ny = {}\nyaw = {}\n",
            start[0], start[1], start[2]
        );
        for w in &walls {
            text += &format!(
                "[[walls]]\ncenter = [{}, {}]\nsize = [{}, {}]\nyaw = {}\n",
                w[0], w[1], w[2], w[3], w[4]
            );
        }
        match World::from_toml(&text, "hostile.toml") {
            Err(e) => prop_assert!(matches!(e, Error::Format { .. }), "{e}"),
            Ok(world) => {
                let b = world.bounds();
                let limit = crate::limits::MAX_COORDINATE;
                prop_assert!(b.min.iter().chain(&b.max).all(|v| v.abs() <= limit));
                let robot = std::sync::Arc::new(crate::RobotProfile::builtin("e-puck").unwrap());
                if let Ok(mut sim) = crate::Simulator::new(
                    std::sync::Arc::new(world),
                    robot,
                    crate::SimConfig::default(),
                ) {
                    sim.step(6.0, 5.0).unwrap();
                    prop_assert!(sim.pose().iter().all(|v| v.is_finite()));
                }
            }
        }
    }
}

#[test]
fn a_grid_without_its_sizes_has_the_generated_mazes_cells_and_walls() {
    let map = "map = \"\"\"\n+--+--+\n|S  G |\n+--+--+\n\"\"\"\n";
    let drawn = parse(&format!("[grid]\n{map}")).unwrap();
    let sized = parse(&format!(
        "[grid]\ncell_size = 0.25\nwall_thickness = 0.01\n{map}"
    ))
    .unwrap();
    assert_eq!(drawn, sized);
    let other = parse(&format!("[grid]\ncell_size = 0.3\n{map}")).unwrap();
    assert_ne!(drawn, other);
}

#[test]
fn a_grid_of_the_wrong_width_names_the_columns_of_its_example_and_the_nearest_widths() {
    // 9 characters: neither 2 columns (7) nor 3 (10); "+--+--+" is the 2-column example.
    let (_, field, message) =
        format_error("[grid]\nmap = \"\"\"\n+--+--+--\n|S     G|\n+--+--+--\n\"\"\"\n");
    assert_eq!(field, "grid.map");
    assert!(
        message.contains("\"+--+--+\" is 2 columns, 7 characters"),
        "{message}"
    );
    assert!(
        message.contains("found 9; the nearest widths: 7 (2 columns) or 10 (3 columns)"),
        "{message}"
    );
    let (_, _, narrow) = format_error("[grid]\nmap = \"\"\"\n+-+\n|S|\n+-+\n\"\"\"\n");
    assert!(
        narrow.ends_with("found 3; the nearest widths: 4 (1 column)"),
        "{narrow}"
    );
}

#[test]
fn a_misaligned_grid_row_says_how_wide_a_cell_is() {
    let (line, field, message) =
        format_error("[grid]\nmap = \"\"\"\n+--+--+\n|S   G|\n+--+-+\n\"\"\"\n");
    assert_eq!((line, field.as_str()), (7, "grid.map"));
    assert!(message.contains("between corners"), "{message}");
    assert!(message.contains("three characters wide"), "{message}");
    assert!(message.ends_with("found '+'"), "{message}");
}

#[test]
fn a_grid_wall_as_thick_as_its_cell_is_refused_as_the_generator_refuses_it() {
    let map = "map = \"\"\"\n+--+--+\n|S  G |\n+--+--+\n\"\"\"\n";
    for thickness in ["0.25", "0.5", "1e300"] {
        let (_, field, message) = format_error(&format!(
            "[grid]\ncell_size = 0.25\nwall_thickness = {thickness}\n{map}"
        ));
        assert_eq!(field, "grid.wall_thickness", "{thickness}");
        assert!(message.contains("wall thickness < cell size"), "{message}");
    }
    let generated = crate::generator::MazeParams {
        wall_thickness: 0.25,
        ..Default::default()
    };
    let refused = generated.check().unwrap_err().to_string();
    assert!(refused.contains("wall thickness < cell size"), "{refused}");
}
