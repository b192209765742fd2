//! How high walls stand (`height` of a `[[walls]]` entry): what a Webots world's own distance
//! sensors read against (rays pass over a wall lower than them); the import writes each
//! obstacle's top.

mod common;

use common::world;
use mazesim_core::wbt::WbtImport;
use mazesim_core::World;

#[test]
fn a_wall_s_height_is_read_kept_apart_for_sensed_walls_and_written_back() {
    let w = world(
        32.0,
        "[[walls]]\ncenter = [0.5, 0.0]\nsize = [0.01, 0.2]\nheight = 0.06\n\
         [[walls]]\ncenter = [0.06, 0.0]\nsize = [0.01, 0.2]\nheight = 0.02\nsensed_only = true\n\
         [[walls]]\ncenter = [-0.5, 0.0]\nsize = [0.01, 0.2]\n",
    );
    assert_eq!(w.wall_tops(), vec![0.06, f64::INFINITY]);
    assert_eq!(w.sensed_wall_tops(), vec![0.02]);
    let again = World::from_toml(&w.to_toml().unwrap(), "again.toml").unwrap();
    assert_eq!(again.wall_tops(), w.wall_tops());
    assert_eq!(again.sensed_wall_tops(), w.sensed_wall_tops());
}

#[test]
fn a_wall_of_no_height_is_refused_naming_the_field() {
    for height in ["0.0", "-0.1"] {
        let text = format!(
            "format = \"mazesim-world\"\nversion = 1\n\
             [[walls]]\ncenter = [0.5, 0.0]\nsize = [0.01, 0.2]\nheight = {height}\n"
        );
        let error = World::from_toml(&text, "low.toml").unwrap_err().to_string();
        assert!(error.contains("height"), "{error}");
    }
}

#[test]
fn the_import_writes_each_obstacle_s_top() {
    let text = "#VRML_SIM R2023b utf8\n\
        Solid { translation 0.5 0 0.03 boundingObject Box { size 0.1 0.1 0.06 } }\n\
        Solid { translation -0.5 0 0.05 boundingObject Sphere { radius 0.06 } }\n\
        E-puck { }\n";
    let import = WbtImport::from_text(text, "tops.wbt").unwrap();
    assert_eq!(import.obstacle_tops[0], 0.06);
    assert!((import.obstacle_tops[1] - 0.11).abs() < 1e-12);
    let spec = import.to_spec("tops");
    let heights: Vec<_> = spec
        .walls
        .iter()
        .map(|w| w.height.map(|h| h.get()))
        .collect();
    assert_eq!(heights[0], Some(0.06));
    assert!(heights[1..].iter().all(|h| *h == Some(0.11)), "{heights:?}");
}
