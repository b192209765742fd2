use super::*;

fn corridor() -> Place {
    // Three cells of 0.25 m in a row west to east, the goal in the east one.
    Place {
        goal: [0.625, 0.125],
        extent: 0.75,
        corner: [0.0, 0.0],
        cell_size: 0.25,
        origin: [0.0, 0.0],
        grid: Grid { rows: 1, cols: 3 },
    }
}

fn features(kinds: FeatureKinds) -> Features {
    let width = Features::width_of(kinds, 1);
    Features::new(1, kinds, vec![100.0], vec![-10.0; width], vec![10.0; width]).unwrap()
}

#[test]
fn the_goal_ahead_is_forward_in_units_of_the_extent() {
    let mut f = features(FeatureKinds::default());
    f.set_env(0, corridor(), &[[0.625, 0.125]], None, None)
        .unwrap();
    let mut out = vec![0.0; f.width()];
    f.observe(0, &[50.0], [0.125, 0.125, 0.0], [0.5, -0.5], &mut out)
        .unwrap();
    assert_eq!(out, vec![0.5, (0.5f64 / 0.75) as f32, 0.0, 0.5, -0.5]);
}

const PLAN: FeatureKinds = FeatureKinds {
    plan: true,
    explore: true,
    guided: false,
    pose: false,
};

/// Features planning in the corridor, its three cells joined, towards the east one.
fn planned_corridor() -> Features {
    let mut f = features(PLAN);
    let sides = [
        [1.0, 0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ];
    f.set_env(0, corridor(), &[[0.0, 0.0]; 3], Some(&sides), Some(2))
        .unwrap();
    f
}

#[test]
fn the_plan_walks_into_unseen_cells_and_visits_are_counted() {
    let mut f = planned_corridor();
    let mut out = vec![0.0; f.width()];
    f.observe(0, &[0.0], [0.125, 0.125, 0.0], [0.0, 0.0], &mut out)
        .unwrap();
    // The waypoint is the next cell's centre, one cell ahead.
    assert_eq!(&out[3..5], &[1.0, 0.0]);
    // Ahead open, left and right walled, behind walled (west end); one visit here.
    assert_eq!(&out[5..9], &[1.0, 0.0, 0.0, 0.0]);
    assert_eq!(out[13], (1.0f64 / 3.0) as f32);
    // Staying in the cell counts no new visit; a restart forgets them.
    f.observe(0, &[0.0], [0.13, 0.125, 0.0], [0.0, 0.0], &mut out)
        .unwrap();
    assert_eq!(out[13], (1.0f64 / 3.0) as f32);
    f.restart(0).unwrap();
    f.observe(0, &[0.0], [0.13, 0.125, 0.0], [0.0, 0.0], &mut out)
        .unwrap();
    assert_eq!(out[13], (1.0f64 / 3.0) as f32);
}

#[test]
fn bad_indices_and_sizes_are_errors() {
    let mut f = features(FeatureKinds::default());
    let mut out = vec![0.0; f.width()];
    assert!(f.observe(1, &[0.0], [0.0; 3], [0.0; 2], &mut out).is_err());
    assert!(f
        .observe(0, &[0.0, 1.0], [0.0; 3], [0.0; 2], &mut out)
        .is_err());
    assert!(f.set_env(0, corridor(), &[], None, None).is_err());
    assert!(f
        .set_env(0, corridor(), &[[0.0; 2]], None, Some(3))
        .is_err());
    assert!(Features::new(1, FeatureKinds::default(), vec![1.0], vec![0.0], vec![1.0]).is_err());
}

#[test]
fn a_restored_state_goes_on_as_the_original() {
    let mut f = planned_corridor();
    let mut out = vec![0.0; f.width()];
    f.observe(0, &[0.0], [0.125, 0.125, 0.0], [0.0, 0.0], &mut out)
        .unwrap();
    let mut copy = features(PLAN);
    copy.restore(&f.state()).unwrap();
    let mut again = out.clone();
    f.observe(0, &[0.0], [0.375, 0.125, 0.0], [0.0, 0.0], &mut out)
        .unwrap();
    copy.observe(0, &[0.0], [0.375, 0.125, 0.0], [0.0, 0.0], &mut again)
        .unwrap();
    assert_eq!(out, again);
    assert!(copy.restore(&f.state()[1..]).is_err());
    assert!(copy.restore(&[]).is_err());
}

#[test]
fn issue_35_non_finite_scales_and_bounds_are_refused_so_every_feature_stays_finite() {
    let kinds = FeatureKinds::default();
    let width = Features::width_of(kinds, 1);
    let (low, high) = (vec![-1.0_f32; width], vec![1.0_f32; width]);
    for scale in [f64::NAN, f64::INFINITY, 0.0, -1.0] {
        let made = Features::new(1, kinds, vec![scale], low.clone(), high.clone());
        assert!(made.is_err(), "scale {scale}");
    }
    for bad in [f32::NAN, f32::INFINITY, 2.0] {
        let mut low = low.clone();
        low[width - 1] = bad;
        assert!(
            Features::new(1, kinds, vec![1.0], low, high.clone()).is_err(),
            "low {bad}"
        );
    }
    assert!(Features::new(1, kinds, vec![1.0], low, high).is_ok());
}

#[test]
fn bounds_out_of_order_or_nan_are_refused_naming_the_first_pair() {
    assert!(check_ordered(&[0.0, -1.0], &[0.0, f32::INFINITY], "bounds").is_ok());
    for (low, high, index) in [
        ([0.0, 2.0], [1.0, 1.0], 1),
        ([f32::NAN, 0.0], [1.0, 1.0], 0),
        ([0.0, 0.0], [1.0, f32::NAN], 1),
    ] {
        let message = check_ordered(&low, &high, "bounds")
            .unwrap_err()
            .to_string();
        assert!(message.contains(&format!("low[{index}]")), "{message}");
    }
}
