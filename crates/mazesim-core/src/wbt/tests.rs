//! The importer on small hand-written worlds: conventions of each era, shapes, PROTOs, robots
//! and the warnings for what is not imported.

use std::f64::consts::{FRAC_PI_2, PI};

use super::convert::polygon_sides;
use super::{Document, Obstacle, RobotChoice, WbtImport};
use crate::error::{Error, Result};

fn import(text: &str) -> WbtImport {
    WbtImport::from_text(text, "test.wbt").unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn the_box(o: &Obstacle) -> ([f64; 2], [f64; 2], f64) {
    match *o {
        Obstacle::Box { center, size, yaw } => (center, size, yaw),
        Obstacle::Circle { .. } => panic!("expected a box, found {o:?}"),
    }
}

fn warned(import: &WbtImport, words: &str) -> bool {
    import.warnings.iter().any(|w| w.contains(words))
}

#[test]
fn legacy_worlds_convert_protos_primitives_and_raw_robots() {
    let w = import(
        "#VRML_SIM V8.5 utf8\nWorldInfo { basicTimeStep 64 }\n\
         Wall { translation 0 0 -1 rotation 0 1 0 1.5708 size 1 0.1 0.05 }\n\
         Solid { translation 1 0.05 0 boundingObject Cylinder { radius 0.1 height 0.1 } }\n\
         DifferentialWheels { translation 0 0 0.5 rotation 0 1 0 3.14159 children [\n\
           DistanceSensor { name \"ps0\" } ] boundingObject Box { size 1 1 1 } }\n",
    );
    assert_eq!(w.basic_time_step_ms, 64.0);
    // Wall at NUE (0, 0, -1) = ENU (1, 0); turned 90 degrees about up; 1 m long, 0.05 thick.
    let (center, size, yaw) = the_box(&w.obstacles[0]);
    assert!(close(center[0], 1.0) && close(center[1], 0.0), "{center:?}");
    let long_along_y = close(size[0], 0.05) && close(size[1], 1.0);
    assert!(long_along_y, "{size:?}");
    assert!((yaw - FRAC_PI_2).abs() < 1e-4, "{yaw}");
    // A Y-up cylinder stands upright: a circle at NUE (1, _, 0) = ENU (0, -1).
    assert_eq!(
        w.obstacles[1],
        Obstacle::Circle {
            center: [-0.0, -1.0],
            radius: 0.1
        }
    );
    // The raw robot faces NUE -z turned by pi about y: ENU -x, at NUE z 0.5 = ENU x -0.5.
    let [x, y, heading] = w.robot.unwrap();
    assert!(close(x, -0.5) && close(y, 0.0) && (heading.abs() - PI).abs() < 1e-4);
    assert_eq!(w.obstacles.len(), 2, "the robot's own body is no obstacle");
}

#[test]
fn new_files_saying_nue_are_turned_as_a_whole() {
    let w = import(
        "#VRML_SIM R2023b utf8\nWorldInfo { coordinateSystem \"NUE\" }\n\
         Solid { translation 1 0.05 0 boundingObject Box { size 0.1 0.1 0.2 } }\n\
         E-puck { rotation 1 0 0 -1.5707963 }\n",
    );
    let (center, size, _) = the_box(&w.obstacles[0]);
    assert!(
        close(center[0], 0.0) && close(center[1], -1.0),
        "{center:?}"
    );
    // Box x (0.1) runs along ENU -y, box z (0.2) along ENU -x.
    assert!(close(size[0].min(size[1]), 0.1) && close(size[0].max(size[1]), 0.2));
    let [_, _, heading] = w.robot.unwrap();
    assert!((heading + FRAC_PI_2).abs() < 1e-6, "{heading}");
    assert!(!warned(&w, "tilted"), "{:?}", w.warnings);
}

#[test]
fn a_body_built_y_up_and_stood_upright_in_a_z_up_file_is_read_as_y_up() {
    // Forward along its local -z, up its local y, wheels' axes along x (RoboCup Junior's
    // e-puck-based PROTOs): its rotation stands it up, so it faces +y, its GPS 1.85 cm up.
    let text = "#VRML_SIM R2023b utf8\n\
        Robot { rotation 1 0 0 1.5708 children [\n\
          GPS { translation 0 0.0185 0 }\n\
          DistanceSensor { translation 0 0.03 -0.035 rotation 0 1 0 1.5708 name \"front\" }\n\
          HingeJoint { jointParameters HingeJointParameters { axis -1 0 0 }\n\
            device [ RotationalMotor { name \"left wheel motor\" } ] }\n\
          HingeJoint { jointParameters HingeJointParameters { axis -1 0 0 }\n\
            device [ RotationalMotor { name \"right wheel motor\" } ] }\n\
        ] controller \"drive\" }\n\
        Robot { translation 0.5 0 0 name \"level\" controller \"other\" }\n";
    let w = import(text);
    // The robot the run simulates; its model its node type (no name, model or ps0 says e-puck).
    assert_eq!(w.robots[0].profile, Some("e-puck"), "{:?}", w.warnings);
    assert_eq!(w.robot_model.as_deref(), Some("Robot"), "{:?}", w.warnings);
    let [x, y, heading] = w.robot.unwrap();
    assert!(close(x, 0.0) && close(y, 0.0), "{x} {y}");
    assert!((heading - FRAC_PI_2).abs() < 1e-4, "{heading}");
    assert!(!warned(&w, "tilted"), "{:?}", w.warnings);
    let flags: Vec<bool> = w.robots.iter().map(|r| r.y_up).collect();
    assert_eq!(flags, [true, false]);
    let at = |name: &str| {
        let device = w.extension_devices.iter().find(|d| d.name == name);
        device.unwrap_or_else(|| panic!("no {name}: {:?}", w.extension_devices))
    };
    let [gx, gy, gz] = at("gps").translation;
    assert!(
        close(gx, 0.0) && close(gy, 0.0) && (gz - 0.0185).abs() < 1e-9,
        "{gx} {gy} {gz}"
    );
    let front = at("front");
    let [fx, fy, fz] = front.translation;
    assert!((fx - 0.035).abs() < 1e-9 && close(fy, 0.0) && (fz - 0.03).abs() < 1e-9);
    assert!(
        front.yaw.abs() < 1e-4 && front.pitch.abs() < 1e-4,
        "{}",
        front.yaw
    );
    // Its Z-up twin, and every robot of a file before R2022a, read alike.
    let z_up = text
        .replace("rotation 1 0 0 1.5708 ", "")
        .replace("translation 0 0.0185 0", "translation 0 0 0.0185");
    let twin = import(&z_up);
    assert!(!twin.robots[0].y_up);
    assert!(close(twin.robot.unwrap()[2], 0.0));
    let old = import(
        &text
            .replace("R2023b", "R2021a")
            .replace("rotation 1 0 0 1.5708 ", ""),
    );
    assert_eq!(
        old.robots.iter().map(|r| r.y_up).collect::<Vec<_>>(),
        [true, true]
    );
    // Facing the file's -z: mazesim's +x.
    assert!(old.robot.unwrap()[2].abs() < 1e-4, "{:?}", old.robot);
}

#[test]
fn shapes_nest_scale_and_reuse() {
    let w = import(
        "#VRML_SIM R2023b utf8\n\
         DEF S Solid { translation 1 0 0 rotation 0 0 1 1.5708 boundingObject Group { children [\n\
           Transform { translation 0.5 0 0.05 scale 2 1 1 children [ DEF B Shape { geometry Box { size 0.1 0.2 0.1 } } ] }\n\
           Pose { translation 0 0 0.05 children [ USE B ] } ] } }\n\
         Solid { translation 3 0 0 boundingObject USE B }\n",
    );
    assert_eq!(w.obstacles.len(), 3);
    let (c0, s0, _) = the_box(&w.obstacles[0]);
    assert!(
        (c0[0] - 1.0).abs() < 1e-5 && (c0[1] - 0.5).abs() < 1e-5,
        "{c0:?}"
    );
    assert!(
        close(s0[0], 0.2) && close(s0[1], 0.2),
        "scale doubles x: {s0:?}"
    );
    let (c2, s2, yaw2) = the_box(&w.obstacles[2]);
    assert_eq!((c2, s2, yaw2), ([3.0, 0.0], [0.1, 0.2], 0.0));
}

#[test]
fn a_known_robot_proto_without_a_controller_field_is_a_robot() {
    let w = import(
        "#VRML_SIM R2023b utf8\nPioneer3dx { translation 1 2 0 rotation 0 0 1 0.5 }\nE-puck { translation 0.1 0 0 }\n",
    );
    // The e-puck wins over the robot it would stand in for.
    assert_eq!(w.robot, Some([0.1, 0.0, 0.0]));
    assert_eq!(w.robot_model.as_deref(), Some("E-puck"));
    // The robot's line tells it from the other robot (for the controller's name and fields).
    assert_eq!(w.robot_line, Some(3));
    assert!(warned(
        &w,
        "line 2: Pioneer3dx: a robot that is not an e-puck (Pioneer3dx): its controller runs, its body does not move; its collision shapes are static obstacles"
    ));
    // Its shapes are inside its PROTO: its published footprint stands for them.
    assert!(warned(
        &w,
        "line 2: Pioneer3dx: its collision shapes are inside the Pioneer3dx PROTO: it stands as a disc"
    ));
    assert!(!warned(&w, "in its place"), "{:?}", w.warnings);
    let alone =
        import("#VRML_SIM R2023b utf8\nPioneer3dx { translation 1 2 0 rotation 0 0 1 0.5 }\n");
    assert_eq!(alone.robot, Some([1.0, 2.0, 0.5]));
    assert_eq!(alone.robot_model.as_deref(), Some("Pioneer3dx"));
    assert_eq!(alone.robot_line, Some(2));
    assert_eq!(alone.robot_profile, "e-puck");
    assert!(warned(
        &alone,
        "a run of one controller simulates the e-puck in its place"
    ));
}

/// A two-wheeled robot built by hand as in Webots' own example worlds: Solid children, two
/// HingeJoints whose RotationalMotors have the e-puck's names, sensors of its own names.
const HAND_BUILT: &str = "Robot { translation 0.1 0.2 0 name \"robot1\" controller \"slave\"\n\
    children [ HingeJoint { device [ RotationalMotor { name \"left wheel motor\" } ]\n\
      endPoint Solid { translation 0 0.045 0.025 } }\n\
    HingeJoint { device [ RotationalMotor { name \"right wheel motor\" } ]\n\
      endPoint Solid { translation 0 -0.045 0.025 } }\n\
    DistanceSensor { name \"ds0\" } ]\n\
  boundingObject Cylinder { height 0.08 radius 0.045 } }\n";

#[test]
fn a_robot_built_by_hand_with_the_e_puck_s_wheel_motors_is_simulated_in_every_run() {
    let text = format!("#VRML_SIM R2021c utf8\n{HAND_BUILT}Robot {{ name \"Driver\" controller \"driver\" supervisor TRUE }}\n");
    // The whole world's import and the run of its controller alone decide alike.
    let whole = import(&text);
    let alone = WbtImport::from_text_for(&text, "test.wbt", Some("slave")).unwrap();
    for w in [&whole, &alone] {
        // Simulated, its model its node type: its name does not say e-puck, nor does a ps0.
        assert_eq!(w.robot_model.as_deref(), Some("Robot"), "{:?}", w.warnings);
        assert_eq!(w.robots[0].profile, Some("e-puck"));
        assert_eq!(w.robots[1].profile, None);
        assert!(!warned(w, "in its place"), "{:?}", w.warnings);
        assert!(warned(w, "line 9: Robot \"Driver\": a robot that is not an e-puck (Robot): its controller runs, its body does not move; neither it nor a Solid among its children has a boundingObject, so it is no obstacle"), "{:?}", w.warnings);
    }
    // One wheel motor of that name is not enough (beside a linear motor: no second wheel).
    let one = text.replacen(
        "RotationalMotor { name \"right wheel motor\" }",
        "LinearMotor { name \"arm motor\" }",
        1,
    );
    assert_ne!(one, text);
    assert_eq!(import(&one).robots[0].profile, None);
}

/// A two-wheeled robot of its own build (motors named as its author likes, `motor_1`): each of
/// two HingeJoints turns one about parallel axes through distinct anchors.
fn own_build(second_axis: &str, second_anchor: &str) -> String {
    format!(
        "#VRML_SIM R2025a utf8\nRobot {{ translation 0.3 0 0 children [\n\
         HingeJoint {{ jointParameters HingeJointParameters {{ axis 0 1 0 anchor 0 0.045 0.025 }}\n\
           device [ RotationalMotor {{ name \"motor_1\" }} ] endPoint Solid {{ }} }}\n\
         Pose {{ children [ HingeJoint {{ jointParameters HingeJointParameters {{ axis {second_axis} anchor {second_anchor} }}\n\
           device [ RotationalMotor {{ name \"motor_2\" }} PositionSensor {{ }} ] endPoint Solid {{ }} }} ] }}\n\
         ] controller \"drive\" }}\n"
    )
}

#[test]
fn a_two_wheeled_robot_of_its_own_build_is_the_robot_the_run_simulates() {
    let w = import(&own_build("0 1 0", "0 -0.045 0.025"));
    // Its node type is its model; the e-puck's profile, given its own wheels by the run.
    assert_eq!(w.robot_model.as_deref(), Some("Robot"), "{:?}", w.warnings);
    assert_eq!(w.robots[0].profile, Some("e-puck"));
    assert!(!warned(&w, "not an e-puck"), "{:?}", w.warnings);
    // Hinges about crossed axes (a pan and tilt head), or on one anchor, are no drive.
    for (axis, anchor) in [("0 0 1", "0 -0.045 0.025"), ("0 1 0", "0 0.045 0.025")] {
        let w = import(&own_build(axis, anchor));
        assert_eq!(w.robots[0].profile, None, "{axis} {anchor}");
        assert!(
            warned(&w, "a robot that is not an e-puck (Robot)"),
            "{:?}",
            w.warnings
        );
    }
}

/// A supervisor's world as it runs, after it imported a robot that is not an e-puck (line 4 on:
/// after the file's own three lines).
const RUNNING_WITH_A_ROVER: &str = "#VRML_SIM R2023b utf8\n\
    Robot { name \"spawner\" controller \"spawner\" supervisor TRUE }\n\
    E-puck { translation 0.1 0 0 controller \"cruise\" }\n\
    Robot { translation -0.5 0.3 0.05 name \"rover\" controller \"rove\"\n\
      boundingObject Box { size 0.04 0.3 0.1 } }\n\
    Robot { translation 0.5 0.3 0.05 name \"probe\" controller \"probe\" }\n";

#[test]
fn issue_33_a_robot_imported_while_the_world_runs_is_warned_of_as_the_run_makes_it() {
    // Whichever run it is (the whole world's or one controller's), mazesim starts no
    // controller for a robot a supervisor imports unless it is an e-puck.
    for line in [None, Some(3)] {
        let choice = RobotChoice {
            line,
            imported_from: Some(4),
            ..RobotChoice::default()
        };
        let w = WbtImport::from_text_for(RUNNING_WITH_A_ROVER, "running.wbt", choice).unwrap();
        assert!(warned(&w, "line 4: Robot \"rover\": a robot that is not an e-puck (Robot): imported while the world runs: its controller does not start, its body does not move; its collision shapes are static obstacles"), "{:?}", w.warnings);
        assert!(warned(&w, "line 6: Robot \"probe\": a robot that is not an e-puck (Robot): imported while the world runs: its controller does not start, its body does not move; neither it nor a Solid among its children has a boundingObject"), "{:?}", w.warnings);
        assert!(
            !warned(
                &w,
                "\"rover\": a robot that is not an e-puck (Robot): its controller runs"
            ),
            "{:?}",
            w.warnings
        );
        assert_eq!(w.obstacles.len(), 1, "the rover's box");
    }
    // In the world file itself, the same robot's controller runs.
    let w = import(RUNNING_WITH_A_ROVER);
    assert!(warned(&w, "line 4: Robot \"rover\": a robot that is not an e-puck (Robot): its controller runs, its body does not move; its collision shapes are static obstacles"), "{:?}", w.warnings);
}

#[test]
fn a_bodiless_supervisor_alone_is_told_apart_by_run() {
    let w = import(
        "#VRML_SIM R2025a utf8\nRobot { name \"boss\" controller \"spawn\" supervisor TRUE }\n",
    );
    assert!(warned(&w, "line 2: Robot \"boss\": a robot that is not an e-puck (Robot): a run of one controller simulates the e-puck in its place, at its pose, its own body, wheels and devices not imported; a run of the whole world simulates nothing in its place: its controller runs, its body does not move"), "{:?}", w.warnings);
}

#[test]
fn what_is_not_understood_is_reported_not_fatal() {
    let w = import(
        "#VRML_SIM R2023b utf8\nEXTERNPROTO \"https://x/protos/Chair.proto\"\n\
         Chair { }\nFancyNode { }\n\
         Solid { rotation 1 0 0 0.5 translation 0 0 0.02 boundingObject Box { size 0.1 0.1 0.1 } }\n\
         Solid { boundingObject Mesh { url \"x.obj\" } }\n\
         Solid { translation 0 0 -0.05 boundingObject Box { size 9 9 0.1 } }\n\
         Solid { translation 0 0 0.5 boundingObject Box { size 1 1 0.1 } }\n\
         Solid { physics Physics { } boundingObject Box { } }\n\
         WoodenBox { mass 2 }\nSolid { boundingObject USE NOPE }\n\
         Robot { name \"pioneer\" }\n",
    );
    for words in [
        "Chair: an unknown PROTO",
        "FancyNode: a node type mazesim does not import",
        "does not stand upright",
        "a Mesh bounding object",
        "passes over the robot",
        "line 9: Solid: an object with physics: imported as a static obstacle",
        "line 10: WoodenBox: an object with physics: imported as a static obstacle",
        "USE NOPE",
        "\"pioneer\": a robot that is not an e-puck (Robot): a run of one controller simulates the e-puck in its place",
    ] {
        assert!(
            warned(&w, words),
            "no warning with {words:?} in {:#?}",
            w.warnings
        );
    }
    // The tilted box (as its enclosing box) and the two objects with physics stay; the floor
    // slab is silently dropped.
    assert_eq!(w.obstacles.len(), 3);
    assert_eq!(w.robot, Some([0.0, 0.0, 0.0]));
    assert_eq!(w.robot_model.as_deref(), Some("Robot"));
    assert_eq!(w.robot_profile, "e-puck");
}

#[test]
fn a_sheet_lower_than_the_e_puck_s_body_is_floor_it_stands_on() {
    // A region marked on the floor by a Solid whose bounding box is 1 mm thick and 1 mm up
    // (its top 1.5 mm high): the e-pucks start on it, as in Webots; a 3 mm high one is a wall.
    let w = import(
        "#VRML_SIM R2023b utf8\n\
         Solid { translation 1 1 0.001 boundingObject Box { size 2 2 0.001 } }\n\
         Solid { translation -1 -1 0.0015 boundingObject Box { size 0.5 0.5 0.003 } }\n\
         E-puck { translation 1 1 0 }\n",
    );
    assert!(
        warned(
            &w,
            "a collision shape 1.5 mm high: the robot stands and drives on it"
        ),
        "{:#?}",
        w.warnings
    );
    assert_eq!(w.obstacles.len(), 1);
    let (center, size, _) = the_box(&w.obstacles[0]);
    assert!(
        close(center[0], -1.0) && close(size[0], 0.5),
        "{center:?} {size:?}"
    );
}

#[test]
fn circles_become_polygons_in_the_world() {
    let w = import(
        "#VRML_SIM R2023b utf8\n\
         Solid { translation 0.2 0.3 0.1 boundingObject Cylinder { radius 0.05 height 0.2 } }\n\
         Solid { translation 0 0 0.05 rotation 1 0 0 1.5708 boundingObject Cylinder { radius 0.05 height 0.4 } }\n\
         E-puck { }\n",
    );
    assert_eq!(
        w.obstacles[0],
        Obstacle::Circle {
            center: [0.2, 0.3],
            radius: 0.05
        }
    );
    // A cylinder lying along y: its footprint is 0.1 x 0.4.
    let (_, size, _) = the_box(&w.obstacles[1]);
    assert!((size[0].min(size[1]) - 0.1).abs() < 1e-4 && (size[0].max(size[1]) - 0.4).abs() < 1e-4);
    assert!(warned(&w, "kept as a circle"));
    let world = w.to_world("round").unwrap();
    assert_eq!(world.walls().len(), polygon_sides(0.05) + 1);
}

#[test]
fn proto_defaults_and_arena_fields() {
    let w = import(
        "#VRML_SIM R2022a utf8\n\
         RectangleArena { translation 1 1 0 floorSize 2 1 wallThickness 0.02 }\n\
         Wall { }\nSolidBox { translation 0 0 0.05 size 0.1 0.2 0.1 }\n\
         SolidBox { translation 0 0 0.05 enableBoundingObject FALSE }\n\
         WoodenBox { translation 0 0 0.05 size 5 0.1 0.1 }\n",
    );
    let boxes: Vec<_> = w.obstacles.iter().map(the_box).collect();
    assert_eq!(boxes.len(), 4 + 1 + 1 + 1);
    let same = |a: [f64; 2], b: [f64; 2]| close(a[0], b[0]) && close(a[1], b[1]);
    assert!(
        same(boxes[0].0, [2.01, 1.0]) && same(boxes[0].1, [0.02, 1.0]),
        "{boxes:?}"
    );
    assert!(
        same(boxes[2].0, [1.0, 1.51]) && same(boxes[2].1, [2.04, 0.02]),
        "{boxes:?}"
    );
    assert!(
        same(boxes[4].1, [0.2, 1.0]),
        "Wall's default size 0.2 1 2.4"
    );
    assert!(same(boxes[6].1, [3.0, 0.1]), "WoodenBox clamps to 3 m");
    assert!(warned(&w, "clamped"));
}

#[test]
fn a_use_explosion_stays_bounded() {
    let mut text = String::from(
        "#VRML_SIM R2023b utf8\nDEF L0 Solid { boundingObject Box { size 0.1 0.1 0.1 } }\n",
    );
    for level in 1..40 {
        let prev = level - 1;
        text.push_str(&format!(
            "DEF L{level} Group {{ children [ USE L{prev} USE L{prev} ] }}\n"
        ));
    }
    let Err(Error::Format { message, .. }) = WbtImport::from_text(&text, "test.wbt") else {
        panic!("refused")
    };
    assert!(message.contains("once every USE is expanded"), "{message}");
}

#[test]
fn more_node_bodies_than_a_world_holds_are_refused_before_any_token() {
    // 600,000 Solids took 2 GB of tokens and tree before the node count refused them; a byte
    // scan refuses them first. Braces in strings and comments are no node bodies.
    let body = "Solid { children [ Shape { geometry Box { size 0.1 0.1 0.1 } } ] }\n";
    let bodies_each = 3;
    let count = (super::parser::MAX_EXPANDED_NODES as usize) / bodies_each + 1;
    let text = format!("#VRML_SIM R2023b utf8\n{}", body.repeat(count));
    let Err(Error::Format { message, .. }) = Document::parse(&text, "many.wbt") else {
        panic!("refused")
    };
    assert!(
        message.contains("found more node bodies than that"),
        "{message}"
    );
    let quoted = format!(
        "#VRML_SIM R2023b utf8\n# {{{{{{\nSolid {{ name \"{}\" }}\n",
        "{".repeat(2_000_000)
    );
    assert!(Document::parse(&quoted, "quoted.wbt").is_ok());
}

#[test]
fn bad_world_info_values_fall_back_with_a_warning() {
    let w =
        import("#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep -4 coordinateSystem \"EUN\" }\n");
    assert_eq!(w.basic_time_step_ms, 32.0);
    assert!(warned(&w, "basicTimeStep") && warned(&w, "EUN"));
}

#[test]
fn invalid_utf8_is_a_located_error() {
    let err = WbtImport::from_bytes(b"#VRML_SIM R2023b utf8\nSolid { name \"\xff\" }", "b.wbt")
        .unwrap_err();
    assert!(err.to_string().starts_with("b.wbt:2:15:"), "{err}");
}

// --- the reader ---

const HEADER: &str = "#VRML_SIM R2023b utf8\n";

fn parse(body: &str) -> Result<Document> {
    Document::parse(&format!("{HEADER}{body}"), "t.wbt")
}

#[test]
fn reads_nodes_fields_lists_def_and_use() {
    let doc = parse(
        "EXTERNPROTO \"webots://x/E-puck.proto\"\nIMPORTABLE EXTERNPROTO \"../W.proto\"\n\
         DEF A Solid { translation 1 2 3 children [ DEF S Shape { geometry Box { size 1 1 1 } } ] \
         boundingObject USE S name \"a\" locked TRUE hidden position_0_0 1 2\n }\n\
         DEF A Group { children [ USE A NULL ] }\nE-puck { }",
    )
    .unwrap();
    assert_eq!(doc.roots.len(), 3);
    assert!(doc.declares_proto("E-puck") && doc.declares_proto("W"));
    let solid = doc.node(doc.roots[0]);
    assert_eq!(
        solid.field("translation").unwrap().value.numbers,
        vec![1.0, 2.0, 3.0]
    );
    assert!(
        solid.field("position_0_0").is_none(),
        "hidden lines are skipped"
    );
    let shape = solid.field("children").unwrap().value.nodes[0];
    assert_eq!(
        solid.field("boundingObject").unwrap().value.nodes,
        vec![shape]
    );
    let group = doc.node(doc.roots[1]);
    assert_eq!(
        group.field("children").unwrap().value.nodes,
        vec![doc.roots[0]]
    );
}

#[test]
fn use_refers_to_the_most_recent_earlier_def() {
    let doc = parse("DEF X Box { } DEF X Sphere { } Group { children [ USE X ] }").unwrap();
    let group = doc.node(doc.roots[2]);
    let used = group.field("children").unwrap().value.nodes[0];
    assert_eq!(doc.node(used).type_name, "Sphere");
}

#[test]
fn errors_carry_line_column_and_field() {
    let err = parse("Solid {\n  translation 1 2 3\n  children [ Shape { ] }\n").unwrap_err();
    let text = err.to_string();
    assert!(text.starts_with("t.wbt:4:22:"), "{text}");
    assert!(text.contains("Solid.children.Shape"), "{text}");
    assert!(parse("Solid { translation }").is_err());
    assert!(parse("Solid {").is_err());
    let deep = "Group { children [ ".repeat(60);
    assert!(parse(&deep).unwrap_err().to_string().contains("levels"));
}

#[test]
fn a_deep_use_chain_stays_bounded_and_warns_once() {
    let mut text = String::from("#VRML_SIM R2023b utf8\nDEF L0 Pose { children [ ");
    // 45 nested Poses per level: 90 levels of the text, 46 of the walk.
    text.push_str(&"Pose { children [ ".repeat(45));
    text.push_str("Solid { translation 0 0 0.05 boundingObject Box { size 0.1 0.1 0.1 } }");
    text.push_str(&" ] }".repeat(46));
    for level in 1..12 {
        let prev = level - 1;
        text.push_str(&format!(
            "\nDEF L{level} Pose {{ children [ {} USE L{prev} {} ] }}",
            "Pose { children [ ".repeat(45),
            " ] }".repeat(45)
        ));
    }
    let w = import(&text);
    let deep = w
        .warnings
        .iter()
        .filter(|m| m.contains("nest deeper"))
        .count();
    assert_eq!(deep, 1, "{:?}", w.warnings);
    // L0..L3 reach their Solid within 200 levels (46 per level); L4 and later do not.
    assert_eq!(w.obstacles.len(), 4);
}

#[test]
fn a_legacy_arena_swaps_its_floor_size_like_the_converter() {
    // The converter maps NUE x to ENU -y and NUE z to ENU -x: floorSize 3 1 spans 1 m in x, 3 m in y.
    let w = import("#VRML_SIM R2021b utf8\nRectangleArena { floorSize 3 1 }\n");
    let (center, size, _) = the_box(&w.obstacles[0]);
    assert!(
        close(center[0].abs(), 0.505) && close(center[1], 0.0),
        "{center:?}"
    );
    assert!(close(size[0], 0.01) && close(size[1], 3.0), "{size:?}");
}

#[test]
fn the_e_pucks_ground_sensors_module_is_its_own_gs_sensors_not_a_warning() {
    let w = import(
        "#VRML_SIM R2023b utf8\nE-puck {\n  groundSensorsSlot [\n    E-puckGroundSensors {\n    }\n  ]\n}\n",
    );
    assert!(w.warnings.is_empty(), "{:?}", w.warnings);
    assert!(w.extension_devices.is_empty());
    // Anything else in the slot is still reported.
    let other =
        import("#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [ LineSensorBar { } ] }\n");
    assert!(warned(
        &other,
        "LineSensorBar: in the robot's groundSensorsSlot"
    ));
}

#[test]
fn the_e_puck_of_the_controller_that_runs_is_the_robot() {
    let text = "#VRML_SIM R2023b utf8\nE-puck { translation 0.1 0 0 controller \"leader\" }\nE-puck { translation -0.3 0.2 0 controller \"follower\" }\n";
    let follower = WbtImport::from_text_for(text, "two.wbt", Some("follower")).unwrap();
    assert_eq!(follower.robot, Some([-0.3, 0.2, 0.0]));
    assert_eq!(follower.robot_line, Some(3));
    assert!(warned(
        &follower,
        "line 2: E-puck: an e-puck running \"leader\": a run of the controller \"follower\" alone simulates only its first e-puck (line 3)"
    ));
    assert!(!warned(&follower, "a second e-puck"));
    // An e-puck whose node leaves the field out runs its PROTO's default controller.
    let unnamed = text.replace(" controller \"leader\"", "");
    let alone = WbtImport::from_text_for(&unnamed, "two.wbt", Some("follower")).unwrap();
    assert!(warned(
        &alone,
        "line 2: E-puck: an e-puck running \"e-puck_avoid_obstacles\": a run of"
    ));
    // Without a controller, or one no e-puck names, the first e-puck runs, as before.
    for controller in [None, Some("nobody")] {
        let first = WbtImport::from_text_for(text, "two.wbt", controller).unwrap();
        assert_eq!(first.robot, Some([0.1, 0.0, 0.0]));
        assert!(warned(
            &first,
            "line 3: E-puck: a second e-puck: a run of one controller simulates only the first (line 2)"
        ));
    }
}

#[test]
fn only_the_other_e_pucks_warnings_concern_a_run_of_one_controller_alone() {
    let text = "#VRML_SIM R2023b utf8\nSomethingUnknown { }\nE-puck { controller \"a\" }\nE-puck { controller \"b\" }\nE-puck { controller \"a\" }\n";
    let first = WbtImport::from_text_for(text, "three.wbt", Some("b")).unwrap();
    assert_eq!(first.warnings.len(), 3, "{:?}", first.warnings);
    assert_eq!(first.one_controller_warnings.len(), 2);
    for warning in &first.one_controller_warnings {
        assert!(first.warnings.contains(warning));
        assert!(warning.contains("a run of the whole world runs every robot"));
    }
    assert!(!first.one_controller_warnings[0].contains("SomethingUnknown"));
    let unknown = first
        .warnings
        .iter()
        .filter(|w| w.contains("SomethingUnknown"));
    assert_eq!(unknown.count(), 1);
}

#[test]
fn plain_robot_epuck_lists_its_children_devices_but_not_its_own() {
    let w = import(
        "#VRML_SIM R2023b utf8\nRobot { name \"e-puck\" children [\n\
           Pose { translation 0 0 0.04 children [ Compass { } ] }\n\
           DistanceSensor { name \"ps0\" }\n\
           HingeJoint { device [ RotationalMotor { name \"left wheel motor\" }\n\
             TouchSensor { name \"bumper\" } ] endPoint Solid { children [ GPS { } ] } }\n\
         ] }\n",
    );
    assert_eq!(w.robot_model.as_deref(), Some("E-puck"));
    let names: Vec<(&str, &str)> = w
        .extension_devices
        .iter()
        .map(|d| (d.name.as_str(), d.slot.as_str()))
        .collect();
    assert_eq!(
        names,
        [
            ("compass", "children"),
            ("bumper", "children"),
            ("gps", "children")
        ]
    );
    assert!(close(w.extension_devices[0].translation[2], 0.04));
    assert!(!warned(&w, "not an e-puck"));
}

#[test]
fn webots_7_epuck_and_a_downward_sensor() {
    let w = import(
        "#VRML_SIM R2023b utf8\nEPuck { groundSensorsSlot [\n\
           DistanceSensor { name \"ir0\" rotation 0 1 0 1.5708 } ] }\n",
    );
    assert_eq!(w.robot_model.as_deref(), Some("E-puck"));
    assert_eq!(w.robot_profile, "e-puck");
    let sensor = &w.extension_devices[0];
    assert!((sensor.pitch - FRAC_PI_2).abs() < 1e-4, "{}", sensor.pitch);
}

#[test]
fn an_empty_lookup_table_is_kept_apart_from_a_missing_one() {
    // Webots reads through no table where the field is `[]` (a DistanceSensor reads 0, a
    // LightSensor its raw irradiance), and through the node's default where it is left out.
    let w = import(
        "#VRML_SIM R2023b utf8\nE-puck { turretSlot [\n\
           DistanceSensor { name \"empty\" lookupTable [] }\n\
           DistanceSensor { name \"missing\" }\n\
           LightSensor { name \"rows\" lookupTable [ 0 0 0, 2 10 0.1 ] } ] }\n",
    );
    let table = |name: &str| {
        let device = w.extension_devices.iter().find(|d| d.name == name).unwrap();
        let field = device.fields.iter().find(|(f, _)| f == "lookupTable");
        field.map(|(_, value)| value.clone())
    };
    assert_eq!(table("empty"), Some(super::DeviceField::Table(vec![])));
    assert_eq!(table("missing"), None);
    let rows = vec![[0.0, 0.0, 0.0], [2.0, 10.0, 0.1]];
    assert_eq!(table("rows"), Some(super::DeviceField::Table(rows)));
}
#[test]
fn the_e_pucks_ground_slot_is_mounted_as_its_proto_mounts_it() {
    // Before R2022a the slot is turned so that a plain DistanceSensor in it points at the floor,
    // its y axis to the robot's right; since R2022a it is unrotated. Both sit 3 cm forward.
    let old = import(
        "#VRML_SIM R2021a utf8\nE-puck { groundSensorsSlot [\n\
           DistanceSensor { translation 0 0.01 0 name \"ir1\" } ] }\n",
    );
    let sensor = &old.extension_devices[0];
    assert!((sensor.pitch - FRAC_PI_2).abs() < 1e-3, "{}", sensor.pitch);
    let [x, y, _] = sensor.translation;
    assert!(
        (x - 0.03).abs() < 1e-6 && (y + 0.01).abs() < 1e-6,
        "{:?}",
        sensor.translation
    );
    let new = import(
        "#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [\n\
           DistanceSensor { translation 0 0.01 0 name \"ir1\" } ] }\n",
    );
    let sensor = &new.extension_devices[0];
    assert!(sensor.pitch.abs() < 1e-9, "{}", sensor.pitch);
    let [x, y, _] = sensor.translation;
    assert!(
        (x - 0.03).abs() < 1e-6 && (y - 0.01).abs() < 1e-6,
        "{:?}",
        sensor.translation
    );
}

/// Whether every component of two lists of axes is within `tol`.
fn axes_close(found: [[f64; 3]; 3], expected: [[f64; 3]; 3], tol: f64) -> bool {
    (0..3).all(|i| (0..3).all(|j| (found[i][j] - expected[i][j]).abs() < tol))
}

#[test]
fn a_devices_axes_are_its_frame_in_the_robots() {
    // Since R2022a an unturned device reads in the robot's frame.
    let new = import("#VRML_SIM R2023b utf8\nE-puck { turretSlot [ Receiver { } ] }\n");
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(axes_close(new.extension_devices[0].axes, identity, 1e-9));
    // Before, the PROTO's inside is Y-up: x right, y up, z back.
    let old = import("#VRML_SIM R2021a utf8\nE-puck { turretSlot [ Receiver { } ] }\n");
    let y_up = [[0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]];
    assert!(axes_close(old.extension_devices[0].axes, y_up, 1e-9));
    // Its groundSensorsSlot is turned -1.57 rad about the back axis: x down, y right.
    let ground = import("#VRML_SIM R2018b utf8\nE-puck { groundSensorsSlot [ Receiver { } ] }\n");
    let turned = [[0.0, 0.0, -1.0], [0.0, -1.0, 0.0], [-1.0, 0.0, 0.0]];
    assert!(axes_close(ground.extension_devices[0].axes, turned, 1e-3));
    // A device's own rotation composes with its mount's.
    let own = import(
        "#VRML_SIM R2023b utf8\nE-puck { turretSlot [ Receiver { rotation 0 0 1 1.5708 } ] }\n",
    );
    let left = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(axes_close(own.extension_devices[0].axes, left, 1e-4));
}

#[test]
fn a_turret_slot_device_sits_on_top_of_the_turret() {
    // The E-puck PROTO's TURRET_SLOT: 9.5 mm behind the centre, 48.6 mm above the floor, so a
    // GPS 1 cm up in it is 58.6 mm up; the same place in a Y-up world before R2022a.
    for (version, up) in [("R2023b", "0 0 0.01"), ("R2021a", "0 0.01 0")] {
        let text = format!(
            "#VRML_SIM {version} utf8\nE-puck {{ turretSlot [ GPS {{ translation {up} }} ] }}\n"
        );
        let t = import(&text).extension_devices[0].translation;
        let expected = [-0.0095, 0.0, 0.0586];
        assert!(
            (0..3).all(|i| (t[i] - expected[i]).abs() < 1e-9),
            "{version}: {t:?}"
        );
    }
}

#[test]
fn a_numbered_slot_of_a_projects_proto_holds_devices() {
    // A project's own E-puck PROTO may add slots named extensionSlot1, extensionSlot2: their
    // devices are the robot's, as those of a slot whose name ends in Slot; other fields are not.
    let text = "#VRML_SIM R2023b utf8\nE-puck { extensionSlot1 [ GPS { name \"g1\" } ] \
                extensionSlot2 [ Compass { } ] slotNodes [ GPS { name \"no\" } ] }\n";
    let found = import(text).extension_devices;
    let names: Vec<(&str, &str)> = found
        .iter()
        .map(|d| (d.name.as_str(), d.slot.as_str()))
        .collect();
    assert_eq!(
        names,
        [("g1", "extensionSlot1"), ("compass", "extensionSlot2")]
    );
}

#[test]
fn cr_line_ends_read_as_lines() {
    let lf = "#VRML_SIM R2023b utf8\n# a comment\nWoodenBox { translation 0.3 0 0.05 size 0.1 0.1 0.1 }\nE-puck { }\n";
    let cr = import(&lf.replace('\n', "\r"));
    let lf = import(lf);
    assert_eq!(cr.obstacles, lf.obstacles);
    assert_eq!(cr.obstacles.len(), 1);
    assert_eq!(cr.robot_line, Some(4));
}

#[test]
fn issue_33_every_robot_is_listed_with_its_controller() {
    let text = "#VRML_SIM R2023b utf8\n\
        DEF BOSS Robot { translation 0 0 0.5 name \"boss\" controller \"boss\" supervisor TRUE }\n\
        E-puck { translation 0.1 0 0 name \"a\" controller \"worker\" }\n\
        E-puck { translation 0.3 0 0 name \"b\" controller \"worker\" version \"2\" }\n\
        Robot { translation 0.5 0.5 0 controller \"post\" boundingObject Box { size 0.1 0.1 0.1 } }\n";
    let w = WbtImport::from_text_for(text, "swarm.wbt", Some("worker")).unwrap();
    let listed: Vec<_> = w
        .robots
        .iter()
        .map(|r| {
            (
                r.line,
                r.controller.as_deref(),
                r.profile,
                r.name.as_deref(),
            )
        })
        .collect();
    assert_eq!(
        listed,
        [
            (2, Some("boss"), None, Some("boss")),
            (3, Some("worker"), Some("e-puck"), Some("a")),
            (4, Some("worker"), Some("e-puck2"), Some("b")),
            (5, Some("post"), None, None),
        ]
    );
    assert_eq!(w.robots[0].def_name.as_deref(), Some("BOSS"));
    assert_eq!(w.robots[2].pose, [0.3, 0.0, 0.0]);
    // The run of one controller simulates the first e-puck running it.
    assert_eq!(w.robot_line, Some(3));
    // A second e-puck of the same controller is not called one "of another controller".
    assert!(warned(
        &w,
        "line 4: E-puck \"b\": another e-puck running \"worker\" too"
    ));
    assert!(!warned(&w, "another controller"), "{:?}", w.warnings);
    // The plain Robot's collision shape stays, as a static obstacle; the bodiless one adds none.
    assert_eq!(w.obstacles.len(), 1, "{:?}", w.obstacles);
    let Obstacle::Box { center, .. } = w.obstacles[0] else {
        panic!("a box")
    };
    assert!((center[0] - 0.5).abs() < 1e-12 && (center[1] - 0.5).abs() < 1e-12);
}

#[test]
fn issue_33_a_run_of_one_robot_chosen_by_its_line() {
    let text = "#VRML_SIM R2023b utf8\n\
        Robot { name \"boss\" controller \"boss\" children [ Emitter { channel 3 } ] }\n\
        E-puck { translation 0.1 0 0 controller \"worker\" }\n\
        E-puck { translation 0.3 0 0 controller \"worker\" }\n";
    let second = RobotChoice {
        line: Some(4),
        ..RobotChoice::default()
    };
    let w = WbtImport::from_text_for(text, "swarm.wbt", second).unwrap();
    assert_eq!(w.robot, Some([0.3, 0.0, 0.0]));
    assert_eq!(w.robot_line, Some(4));
    let boss = RobotChoice {
        line: Some(2),
        ..RobotChoice::default()
    };
    let w = WbtImport::from_text_for(text, "swarm.wbt", boss).unwrap();
    assert_eq!(w.robot_line, Some(2));
    assert_eq!(w.robot_model.as_deref(), Some("Robot"));
    // The supervisor's own emitter is its device, with its channel.
    assert_eq!(w.extension_devices.len(), 1, "{:?}", w.extension_devices);
    assert_eq!(w.extension_devices[0].kind, "Emitter");
    let channel = w.extension_devices[0]
        .fields
        .iter()
        .find(|(name, _)| name == "channel");
    assert_eq!(
        channel.map(|(_, v)| v),
        Some(&super::DeviceField::Number(3.0))
    );
    assert!(warned(
        &w,
        "line 2: Robot \"boss\": a robot that is not an e-puck (Robot): its controller runs"
    ));
}

/// The reflectance the import paints at (x, y), the last paint on top; `None` for bare floor.
fn painted_at(import: &WbtImport, x: f64, y: f64) -> Option<f64> {
    use crate::world::spec::PaintSpec;
    import.paint.iter().rev().find_map(|p| match p {
        PaintSpec::Rect {
            center,
            size,
            yaw,
            reflectance,
            ..
        } => {
            let (s, c) = yaw.0.sin_cos();
            let (dx, dy) = (x - center[0].0, y - center[1].0);
            let (u, v) = (c * dx + s * dy, -s * dx + c * dy);
            let inside = u.abs() < size[0].0 / 2.0 && v.abs() < size[1].0 / 2.0;
            inside.then_some(reflectance.0)
        }
        PaintSpec::Circle {
            center,
            radius,
            reflectance,
            ..
        } => ((x - center[0].0).hypot(y - center[1].0) < radius.0).then_some(reflectance.0),
        PaintSpec::Polyline { .. } => None,
    })
}

#[test]
fn test_a_line_given_as_an_obj_mesh_outside_any_solid_is_floor_paint() {
    // A black strip 0.6 m long and 2 cm wide, 2 mm thick, as a Wavefront file beside the world,
    // scaled and moved by the Transform as Webots does.
    let dir = std::env::temp_dir().join(format!("mazesim-obj-mesh-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("line")).unwrap();
    std::fs::create_dir_all(dir.join("worlds")).unwrap();
    std::fs::write(
        dir.join("line/strip.obj"),
        "# strip\no strip\nv -30 -1 0\nv 30 -1 0\nv 30 1 0\nv -30 1 0\n\
         v -30 -1 0.1\nv 30 -1 0.1\nv 30 1 0.1\nv -30 1 0.1\nf 1 2 3 4\nf 5/1 6/1 7/1 8/1\n",
    )
    .unwrap();
    let world = dir.join("worlds/line.wbt");
    let text = "#VRML_SIM R2025a utf8\nWorldInfo { }\n\
        Transform { translation 0.2 0.1 0 scale 0.01 0.01 0.02 children [\n\
          Shape { appearance PBRAppearance { baseColor 0 0 0 } geometry Mesh { url [ \"../line/strip.obj\" ] } }\n\
        ] }\n\
        Transform { translation 0 -0.3 0.1 children [ Shape { geometry Box { size 0.1 0.1 0.1 } } ] }\n\
        Pose { translation 0 0.4 0.0005 children [ Shape { appearance Appearance { material Material { diffuseColor 0.5 0.5 0.5 } } geometry Box { size 0.1 0.1 0.001 } } ] }\n\
        Solid { translation 0.5 0.5 0.05 children [ Shape { geometry Box { size 0.1 0.1 0.1 } } ] boundingObject Box { size 0.1 0.1 0.1 } }\n\
        E-puck { }\n";
    let import = WbtImport::from_text(text, &world.display().to_string()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    // The strip spans x 0.2 +- 0.3, y 0.1 +- 0.01: black (0.2) on it, bare floor beside it.
    for x in [-0.05, 0.2, 0.45] {
        assert_eq!(
            painted_at(&import, x, 0.1),
            Some(0.2),
            "on the line at x {x}"
        );
    }
    assert_eq!(painted_at(&import, 0.2, 0.13), None);
    assert_eq!(painted_at(&import, 0.55, 0.1), None);
    // A grey tile 1 mm thick is a mark too: 0.2 + 0.8 * 0.5.
    assert!((painted_at(&import, 0.0, 0.4).unwrap() - 0.6).abs() < 1e-12);
    // A visual-only box that stands on the floor is named, not lost; the Solid's is simulated.
    let dropped: Vec<_> = import
        .warnings
        .iter()
        .filter(|w| w.contains("not imported"))
        .collect();
    assert_eq!(dropped.len(), 1, "{:?}", import.warnings);
    assert!(
        dropped[0].contains("line 6: Shape") && dropped[0].contains("outside any Solid"),
        "{dropped:?}"
    );
    assert_eq!(import.obstacles.len(), 1);
}

#[test]
fn a_track_sheet_raised_a_few_millimetres_in_a_solid_without_bounding_object_is_floor_paint() {
    // A dark sheet 7.5 mm above the floor in a Solid that collides with nothing, as a course's
    // track PROTO models it, and the same sheet 2 cm up: both under the proximity rays. The
    // same sheet 5 cm up is named instead.
    let sheet = |y: f64, z: f64| {
        format!(
            "Solid {{ translation 0 {y} {z} children [ Shape {{ appearance PBRAppearance {{ \
             baseColor 0.17 0.18 0.19 }} geometry IndexedFaceSet {{ coord Coordinate {{ point [ \
             -0.3 -0.01 0, 0.3 -0.01 0, 0.3 0.01 0, -0.3 0.01 0 ] }} coordIndex [ 0 1 2 3 -1 ] \
             }} }} ] }}\n"
        )
    };
    let text = format!(
        "#VRML_SIM R2022b utf8\nWorldInfo {{ }}\n{}{}{}E-puck {{ }}\n",
        sheet(0.0, 0.0075),
        sheet(0.5, 0.05),
        sheet(-0.5, 0.02),
    );
    let import = WbtImport::from_text(&text, "track.wbt").unwrap();
    for y in [0.0, -0.5] {
        let on_track = painted_at(&import, 0.1, y).expect("the raised track is paint");
        assert!((on_track - (0.2 + 0.8 * 0.17)).abs() < 1e-9, "{on_track}");
    }
    assert_eq!(painted_at(&import, 0.1, 0.05), None);
    assert_eq!(painted_at(&import, 0.1, 0.5), None);
    assert!(
        import
            .warnings
            .iter()
            .any(|w| w.starts_with("line 4: Shape") && w.contains("0.050 m above the floor")),
        "{:?}",
        import.warnings
    );
    assert!(import.obstacles.is_empty());
}

#[test]
fn a_road_slab_under_the_proximity_rays_is_paint_with_its_lane_marks_on_top() {
    // A lane follower's road: a dark visual-only slab 1.6 cm thick, a white lane mark 2 mm thick
    // lying on it, and a block whose top is at 3.5 cm (in the proximity rays' way).
    let text = "#VRML_SIM R2025a utf8\nWorldInfo { }\n\
        Pose { translation 0 0 0.008 children [ Shape { appearance PBRAppearance { baseColor 0 0 0 } geometry Box { size 1.5 0.5 0.016 } } ] }\n\
        Pose { translation 0 0 0.017 children [ Shape { appearance PBRAppearance { baseColor 1 1 1 } geometry Box { size 1.5 0.02 0.002 } } ] }\n\
        Pose { translation 0 0.6 0.0175 children [ Shape { geometry Box { size 0.1 0.1 0.035 } } ] }\n\
        E-puck { translation 0 -0.1 0 }\n";
    let import = import(text);
    assert_eq!(painted_at(&import, 0.3, -0.1), Some(0.2)); // the road, black
    assert_eq!(painted_at(&import, 0.3, 0.0), Some(1.0)); // its lane mark, white, on top
    assert_eq!(painted_at(&import, 0.3, 0.3), None); // beside the road
    assert_eq!(painted_at(&import, 0.0, 0.6), None); // the block is no paint...
    assert_eq!(import.sensed_obstacles.len(), 1); // ...but seen by the proximity rays
    assert!(import.obstacles.is_empty());
}

#[test]
fn a_mesh_that_cannot_be_read_or_rises_above_the_floor_is_named() {
    let dir = std::env::temp_dir().join(format!("mazesim-obj-tall-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tall.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n").unwrap();
    let text = "#VRML_SIM R2025a utf8\nWorldInfo { }\n\
        Shape { geometry Mesh { url [ \"tall.obj\" ] } }\n\
        Shape { geometry Mesh { url [ \"absent.obj\" ] } }\n\
        Shape { geometry Mesh { url [ \"https://example.org/m.obj\" ] } }\n\
        Shape { geometry Mesh { url [ \"part.stl\" ] } }\n";
    let import = WbtImport::from_text(text, &dir.join("w.wbt").display().to_string()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(import.paint.is_empty());
    for (line, words) in [
        (3, "reaching 1.000 m above the floor"),
        (4, "absent.obj"),
        (5, "not URLs"),
        (6, "only Wavefront .obj"),
    ] {
        let found = import
            .warnings
            .iter()
            .any(|w| w.starts_with(&format!("line {line}: Mesh")) && w.contains(words));
        assert!(found, "line {line}: {words}: {:?}", import.warnings);
    }
}

#[test]
fn a_y_up_arena_lays_its_image_as_webots_y_up_floor_does() {
    // The Y-up Floor PROTO (R2019b to R2021b) gives its corner (-x/2, -z/2) the texture
    // coordinate (0, 1) and (-x/2, +z/2) the coordinate (0, 0): the image's left column lies
    // towards -x and its top row towards -z. A 2 x 1 m floor, one copy of an image whose
    // top-left quarter is black: black where x < 0 and z < 0, which the NUE to ENU mapping
    // (x, y, z) -> (-z, -x, y) puts where x > 0 and y > 0.
    let mut import = WbtImport::from_text(
        "#VRML_SIM R2021a utf8
RectangleArena { floorSize 2 1 floorTileSize 2 1 floorAppearance Appearance { texture ImageTexture { url [\"t.png\"] } } }\n",
        "old.wbt",
    )
    .unwrap();
    let image = super::floor_texture::GreyImage {
        width: 2,
        height: 2,
        levels: vec![0.0, 1.0, 1.0, 1.0],
    };
    import.paint_floor(&std::collections::BTreeMap::from([(
        "t.png".to_string(),
        image,
    )]));
    let nue = |x: f64, z: f64| painted_at(&import, -z, -x);
    assert_eq!(nue(-0.5, -0.25), Some(0.2), "the image's top-left quarter");
    assert_eq!(nue(0.5, -0.25), Some(1.0), "its top-right quarter");
    assert_eq!(nue(-0.5, 0.25), Some(1.0), "its bottom-left quarter");
    assert_eq!(nue(0.5, 0.25), Some(1.0), "its bottom-right quarter");
    assert_eq!(nue(-0.9, -0.45), Some(0.2), "the floor's corner (-x, -z)");
}

#[test]
fn a_raised_floor_is_lowered_to_zero_with_its_walls_and_paint() {
    // An arena saved 0.85 m up (an expanded RectangleArena scaled by 3 on a table), its wall a
    // Box, a black mark lying on its floor, the e-puck standing on it.
    let raised = |height: f64, robot: f64| {
        import(&format!(
            "#VRML_SIM R2021b utf8\nWorldInfo {{ coordinateSystem \"NUE\" }}\n\
             E-puck {{ translation 0.2 {robot} 0 }}\n\
             Solid {{ translation 0 {height} 0 scale 3 3 3 children [\n\
               Solid {{ name \"floor\" boundingObject Plane {{ }} }}\n\
               Solid {{ translation 0.505 0.05 0 name \"wall\" boundingObject Box {{ size 0.01 0.1 1 }} }}\n\
               Shape {{ appearance PBRAppearance {{ baseColor 0 0 0 }} geometry Box {{ size 0.1 0.0001 0.02 }} }}\n\
             ] }}\n"
        ))
    };
    let w = raised(0.85, 0.8499);
    assert_eq!(w.obstacles.len(), 1, "{:?}", w.warnings);
    let (center, size, _) = the_box(&w.obstacles[0]);
    // NUE x 0.505 * 3 is ENU -y 1.515; the wall is 3 m long and 3 cm thick.
    let wall = close(center[1], -1.515) && close(size[0].max(size[1]), 3.0);
    assert!(
        wall && close(size[0].min(size[1]), 0.03),
        "{center:?} {size:?}"
    );
    assert_eq!(
        w.paint.len(),
        1,
        "the mark lies on the lowered floor: {:?}",
        w.warnings
    );
    assert!(warned(&w, "a floor 0.850 m above the world's origin"));
    assert!(!warned(&w, "passes over the robot"));
    // A robot saved in the air above a floor at 0 falls onto it: nothing is lowered.
    let on_zero = raised(0.0, 0.3);
    assert!(!warned(&on_zero, "above the world's origin"));
    assert_eq!(on_zero.paint.len(), 1);
}

#[test]
fn a_field_value_that_is_no_number_is_refused_naming_the_field_and_its_line() {
    let cases = [
        ("size -1 1e300 nan", "nan", "after its first 2 numbers"),
        ("size 1 inf 1", "inf", "after its first number"),
        ("size 1 1 wide", "wide", "after its first 2 numbers"),
        ("size 1 1e400 1", "1e400", "after its first number"),
        (
            "size -Infinity 1 1",
            "-Infinity",
            "finite numbers, found `-Infinity`",
        ),
        ("size [ 1 NaN 1 ]", "NaN", "after its first number"),
    ];
    for (field, found, says) in cases {
        let text = format!("Solid {{\n  boundingObject Box {{\n    {field} }}\n}}");
        let Err(Error::Format {
            location,
            field,
            message,
        }) = parse(&text)
        else {
            panic!("{text} was read")
        };
        assert_eq!(location.line, 4, "{message}");
        assert_eq!(field, "Solid.boundingObject.Box.size", "{message}");
        assert!(message.contains(&format!("found `{found}`")), "{message}");
        assert!(message.contains(says), "{message}");
    }
    // A field name after numbers is one: a value follows it.
    let doc = parse("Solid { translation 1 2 3 name \"a\" locked TRUE }").unwrap();
    assert_eq!(doc.node(doc.roots[0]).fields.len(), 3);
}

#[test]
fn a_frame_field_of_too_few_numbers_is_refused_as_webots_refuses_it() {
    let cases = [
        (
            "Solid { translation 1 2 rotation 0 0 1 0 }",
            "`translation` to hold 3 numbers, found 2, then `rotation`",
        ),
        (
            "Pose { rotation 0 0 1 }",
            "`rotation` to hold 4 numbers, found 3, then `}`",
        ),
        (
            "Robot { translation 1 wide }",
            "`translation` to hold 3 numbers, found 1, then `wide`",
        ),
    ];
    for (text, says) in cases {
        let Err(Error::Format { message, .. }) = parse(text) else {
            panic!("{text} was read")
        };
        assert!(message.contains(says), "{message}");
    }
    // A non-finite number keeps its own wording; a PROTO's field of the same name is its own.
    let Err(Error::Format { message, .. }) = parse("Solid { translation 1 nan 3 }") else {
        panic!("nan was read")
    };
    assert!(message.contains("finite numbers, found `nan`"), "{message}");
    assert!(parse("MyProto { translation 1 2 }").is_ok());
    assert!(parse("Solid { translation 1 2 3 4 }").is_ok());
}

#[test]
fn a_proto_file_read_as_a_world_is_named_a_proto_file() {
    let proto = "#VRML_SIM R2023b utf8\nPROTO Foo [ ] { Solid { } }\n";
    let err = WbtImport::from_text(proto, "foo.proto")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("expected a Webots world (.wbt), found a Webots PROTO file"),
        "{err}"
    );
    // A world that defines a PROTO inline and uses it is still a world.
    let world = "#VRML_SIM R2023b utf8\nPROTO Foo [ ] { Solid { } }\nFoo { }\n";
    assert!(WbtImport::from_text(world, "w.wbt").is_ok());
}

#[test]
fn a_library_robot_without_readable_shapes_stands_as_its_footprint() {
    let w = import(
        "#VRML_SIM R2023b utf8\nE-puck { translation 0 0 0 }\nThymio2 { translation -0.3 -0.6 0 controller \"<none>\" }\nPioneer3dx { translation 1 0.5 0.0975 rotation 0 0 1 0.5 }\nNao { translation 2 2 0.33 }\n",
    );
    let circles: Vec<([f64; 2], f64)> = w
        .obstacles
        .iter()
        .filter_map(|o| match o {
            Obstacle::Circle { center, radius } => Some((*center, *radius)),
            _ => None,
        })
        .collect();
    assert_eq!(circles.len(), 2, "{circles:?}");
    assert!((circles[0].0[0] + 0.3).abs() < 1e-9 && (circles[0].0[1] + 0.6).abs() < 1e-9);
    assert!((circles[0].1 - 0.056).abs() < 1e-12);
    assert!((circles[1].0[0] - 1.0).abs() < 1e-9 && (circles[1].1 - 0.22).abs() < 1e-12);
    assert!(warned(&w, "line 3: Thymio2: its collision shapes are inside the Thymio2 PROTO: it stands as a disc of radius 0.056 m"), "{:?}", w.warnings);
    assert!(warned(&w, "Thymio2: a robot that is not an e-puck (Thymio2): its controller runs, its body does not move; its collision shapes are static obstacles"), "{:?}", w.warnings);
    // A robot without a known footprint is still no obstacle, and says so.
    assert!(
        warned(
            &w,
            "(Nao): its controller runs, its body does not move; it has no collision shape"
        ),
        "{:?}",
        w.warnings
    );
}

#[test]
fn the_solids_a_robot_holds_are_obstacles_as_its_own_shape_is() {
    // A four-wheeled robot of a course: its board on the Robot, its wheels at joints' endPoint
    // (turned a quarter about x, as wheels are), a bumper DistanceSensor with a box, and a
    // Solid in a Pose. Webots collides with each; a supervisor without a body is no obstacle.
    let w = import(
        "#VRML_SIM R2023b utf8\nE-puck { translation 0 0 0 }\n\
         Robot { translation 1 0 0.05 rotation 0 0 1 1.5708 controller \"mobil\" children [\n\
           HingeJoint { endPoint Solid { translation 0.1 0.06 0 rotation 1 0 0 1.5708\n\
             boundingObject Cylinder { radius 0.04 height 0.02 } } }\n\
           DistanceSensor { translation 0.2 0 0 boundingObject Box { size 0.01 0.01 0.01 } }\n\
           Pose { translation -0.2 0 0 children [ Solid { boundingObject Sphere { radius 0.03 } } ] }\n\
         ] boundingObject Box { size 0.1 0.2 0.05 } }\n\
         Robot { translation -1 0 0 supervisor TRUE controller \"sup\" }\n",
    );
    let near = |x: f64, y: f64| {
        w.obstacles.iter().any(|o| {
            let c = match o {
                Obstacle::Circle { center, .. } => *center,
                Obstacle::Box { center, .. } => *center,
            };
            (c[0] - x).abs() < 1e-3 && (c[1] - y).abs() < 1e-3
        })
    };
    // The robot is turned a quarter: its +x is the world's +y, its +y the world's -x.
    assert_eq!(w.obstacles.len(), 4, "{:?}", w.obstacles);
    assert!(near(1.0, 0.0), "its board: {:?}", w.obstacles);
    assert!(near(0.94, 0.1), "its wheel: {:?}", w.obstacles);
    assert!(near(1.0, 0.2), "its sensor's box: {:?}", w.obstacles);
    assert!(near(1.0, -0.2), "the Solid in its Pose: {:?}", w.obstacles);
    assert!(warned(&w, "line 3: Robot: a robot that is not an e-puck (Robot): its controller runs, its body does not move; its collision shapes are static obstacles"), "{:?}", w.warnings);
    assert!(warned(&w, "(Robot): its controller runs, its body does not move; neither it nor a Solid among its children has a boundingObject, so it is no obstacle"), "{:?}", w.warnings);
}

#[test]
fn a_robot_standing_upside_down_is_said_so() {
    let w = import("#VRML_SIM R2023b utf8\nE-puck { rotation 1 0 0 3.14159 }\n");
    assert!(warned(&w, "upside down"), "{:?}", w.warnings);
    let upright = import("#VRML_SIM R2023b utf8\nE-puck { rotation 0 0 1 3.14159 }\n");
    assert!(!warned(&upright, "upside down"), "{:?}", upright.warnings);
    let old = import("#VRML_SIM V8.5 utf8\nE-puck { rotation 1 0 0 3.14159 }\n");
    assert!(warned(&old, "upside down"), "{:?}", old.warnings);
}

#[test]
fn a_warning_a_node_gives_again_in_the_same_words_is_given_once() {
    // Three thin boxes of one Solid (as the many segments of a flat CircleArena): each would
    // say the same of the same node.
    let thin = |x: f64| {
        format!("Pose {{ translation {x} 0 0.002 children [ Box {{ size 0.1 0.1 0.001 }} ] }}")
    };
    let w = import(&format!(
        "#VRML_SIM R2023b utf8\nSolid {{ name \"flat\" boundingObject Group {{ children [ {} {} {} ] }} }}\n",
        thin(0.0),
        thin(0.3),
        thin(0.6)
    ));
    let floor = w
        .warnings
        .iter()
        .filter(|m| m.contains("imported as floor"));
    assert_eq!(floor.count(), 1, "{:?}", w.warnings);
}

#[test]
fn a_box_proto_with_a_mass_placed_in_the_air_falls_onto_the_floor() {
    // Webots' tutorials place boxes with physics in the air: they fall and stand on the
    // floor. Without a mass a WoodenBox stays where it is, over the robot.
    let w = import(
        "#VRML_SIM R2023b utf8\n\
         WoodenBox { translation 0 0.4 0.175 size 0.1 0.1 0.1 mass 0.05 }\n\
         SolidBox { translation 0.5 0 0.3 size 0.1 0.1 0.1 physics Physics { } }\n\
         WoodenBox { translation 0 -0.4 0.3 size 0.1 0.1 0.1 }\n",
    );
    assert!(
        !warned(&w, "line 2: WoodenBox: a collision shape"),
        "{:?}",
        w.warnings
    );
    assert!(
        !warned(&w, "line 3: SolidBox: a collision shape"),
        "{:?}",
        w.warnings
    );
    assert!(warned(
        &w,
        "line 4: WoodenBox: a collision shape 0.250 m above the floor passes over the robot"
    ));
    assert_eq!(w.bodies.len(), 1, "the light box is a movable body");
    assert_eq!(
        w.obstacles.len(),
        1,
        "the SolidBox stands on the floor, static"
    );
}

#[test]
fn a_pad_of_a_solid_the_robot_drives_on_is_a_floor_mark_of_its_colour() {
    // A black goal pad 2 mm thick with a bounding object: the robot drives on it (floor) and
    // its ground sensors see it black, as a pad of no bounding object. A Solid whose bounding
    // object also holds a post keeps its shapes to itself.
    let pad = |x: f64, post: &str| {
        format!(
            "Solid {{ translation {x} 0 0.001 children [ DEF P Shape {{ \
               appearance PBRAppearance {{ baseColor 0 0 0 }} geometry Box {{ size 0.1 0.1 0.002 }} }} ] \
               boundingObject Group {{ children [ USE P {post} ] }} }}\n"
        )
    };
    let post = "Pose { translation 0 0 0.05 children [ Box { size 0.01 0.01 0.1 } ] }";
    let w = import(&format!(
        "#VRML_SIM R2023b utf8\n{}{}",
        pad(0.3, ""),
        pad(-0.3, post)
    ));
    assert!(warned(&w, "line 2: Solid: a collision shape 2.0 mm high"));
    let world = w.to_world("pad").unwrap();
    let floor = world.floor();
    assert!(close(floor.reflectance_at([0.3, 0.02]), 0.2));
    assert!(close(floor.reflectance_at([-0.3, 0.02]), 1.0));
    assert_eq!(w.obstacles.len(), 1, "the post");
}

#[test]
fn a_solid_whose_bounding_object_lies_on_the_floor_is_a_floor_mark_of_its_colour() {
    // A black tile 1 mm thick with a bounding object (no edge for a wheel to climb), with and
    // without physics: floor the robot drives on, whose colour its ground sensors see.
    let tile = |x: f64, physics: &str| {
        format!(
            "Solid {{ translation {x} 0 0.0005 children [ DEF T Shape {{ \
               appearance PBRAppearance {{ baseColor 0 0 0 }} geometry Box {{ size 0.1 0.1 0.001 }} }} ] \
               boundingObject USE T {physics} }}\n"
        )
    };
    // A slab the floor is made of (its top the floor's, its bottom 1 cm down) shows its colour
    // too; a cone buried under the floor with its Solid adds nothing, and a marker a supervisor
    // keeps under it (no bounding object) is seen by nothing above it, as the import says.
    let slab = "Solid { translation 0 0.3 -0.005 children [ DEF S Shape { \
        appearance PBRAppearance { baseColor 0 0 0 } geometry Box { size 0.1 0.1 0.01 } } ] \
        boundingObject USE S }\n";
    let buried = "Solid { translation 0 -0.3 -0.2 children [ DEF C Shape { \
        appearance PBRAppearance { baseColor 0 0 0 } geometry Cylinder { radius 0.05 height 0.1 } } ] \
        boundingObject USE C }\n\
        Pose { translation 0 -0.3 -0.2 children [ USE C ] }\n";
    let w = import(&format!(
        "#VRML_SIM R2023b utf8\n{}{}{slab}{buried}",
        tile(0.3, ""),
        tile(-0.3, "physics Physics { mass 0.01 }")
    ));
    assert!(w.obstacles.is_empty() && w.bodies.is_empty(), "{w:#?}");
    assert_eq!(w.paint.len(), 3, "{:?}", w.paint);
    assert_eq!(w.warnings.len(), 2, "{:?}", w.warnings);
    assert!(warned(&w, "no robot in the world"));
    assert!(warned(
        &w,
        "a Cylinder shape outside any Solid with a boundingObject"
    ));
    assert!(warned(&w, "under the floor"), "{:?}", w.warnings);
    let world = w.to_world("tiles").unwrap();
    let floor = world.floor();
    assert!(close(floor.reflectance_at([0.3, 0.02]), 0.2));
    assert!(close(floor.reflectance_at([-0.3, 0.02]), 0.2));
    assert!(close(floor.reflectance_at([0.0, 0.32]), 0.2), "the slab");
    assert!(close(floor.reflectance_at([0.0, 0.02]), 1.0));
    assert!(
        close(floor.reflectance_at([0.0, -0.3]), 1.0),
        "the buried cone"
    );
}

#[test]
fn a_box_mark_standing_on_another_axis_than_its_z_is_painted() {
    // A black square sunk to the floor's level in a world of coordinateSystem "NUE" (its y
    // axis up, as a course's T-maze of R2022b writes it, scaled), and a long white strip in
    // a Z-up world turned a quarter turn about its x axis: each stands on an axis other than
    // its own z, and each is a mark of its own footprint, not a shape standing in the air.
    let nue = import(
        "#VRML_SIM R2022b utf8\nWorldInfo { coordinateSystem \"NUE\" }\n\
         Solid { translation 0.01 -0.03425 0.193 scale 1.37173 1.37173 1.37173 children [ \
           DEF B Shape { appearance PBRAppearance { baseColor 0 0 0 } \
           geometry Box { size 0.08 0.05 0.08 } } ] boundingObject USE B }\n",
    );
    assert_eq!(nue.paint.len(), 1, "{:?}", nue.warnings);
    let world = nue.to_world("nue").unwrap();
    let floor = world.floor();
    // Turned from NUE as the import turns every node: the square's centre is at x -0.193,
    // y -0.01, 11 cm wide.
    assert!(close(floor.reflectance_at([-0.193, -0.01]), 0.2));
    assert!(close(floor.reflectance_at([-0.24, -0.055]), 0.2));
    assert!(close(floor.reflectance_at([-0.26, -0.01]), 1.0));
    let turned = import(
        "#VRML_SIM R2023b utf8\n\
         Pose { translation 0 0 0.0005 rotation 1 0 0 1.5708 children [ Shape { \
           appearance PBRAppearance { baseColor 0 0 0 } geometry Box { size 0.4 0.001 0.02 } } ] }\n",
    );
    assert_eq!(turned.paint.len(), 1, "{:?}", turned.warnings);
    let world = turned.to_world("turned").unwrap();
    let floor = world.floor();
    assert!(close(floor.reflectance_at([0.15, 0.005]), 0.2));
    assert!(close(floor.reflectance_at([0.0, 0.02]), 1.0));
}

#[test]
fn a_higher_floor_mark_lies_over_a_lower_one_whichever_the_world_writes_first() {
    // A white line 0.5 mm up, then a black slab whose top is the floor's: the line shows on
    // the slab; of two marks level with each other, the later one shows.
    let w = import(
        "#VRML_SIM R2023b utf8\n\
         Pose { translation 0 0 0.00025 children [ Shape { appearance PBRAppearance { baseColor 1 1 1 } \
           geometry Box { size 0.4 0.02 0.0005 } } ] }\n\
         Pose { translation 0 0 -0.005 children [ Shape { appearance PBRAppearance { baseColor 0 0 0 } \
           geometry Box { size 1 1 0.01 } } ] }\n\
         Pose { translation 0.3 0.3 -0.005 children [ Shape { appearance PBRAppearance { baseColor 1 1 1 } \
           geometry Box { size 0.1 0.1 0.01 } } ] }\n",
    );
    let world = w.to_world("slab").unwrap();
    let floor = world.floor();
    assert!(close(floor.reflectance_at([0.1, 0.0]), 1.0), "the line");
    assert!(close(floor.reflectance_at([0.1, 0.2]), 0.2), "the slab");
    assert!(
        close(floor.reflectance_at([0.3, 0.3]), 1.0),
        "the later level patch"
    );
    assert_eq!(w.paint_owners.len(), w.paint.len());
}
