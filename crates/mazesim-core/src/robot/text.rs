//! A profile written back as the TOML text `RobotProfile::from_toml` reads: what a perturbed
//! profile pickles as, and what a user can save and edit. Reading the text back gives a profile
//! equal to the one written (numbers are written so that they read back to the same bits).

use std::collections::BTreeMap;
use std::sync::Arc;

use super::{ModelFile, ProfileFile, RobotProfile, SensorFile, SensorModel};
use crate::error::{Error, Result};
use crate::world::values::{Finite, NonNegative, Positive, Reflectance, SlipFraction};

/// Names the distinct sensor models of a profile (`model-0`, `model-1`, ... in order of first
/// use) and finds a sensor's.
struct ModelNames<'a> {
    models: Vec<&'a Arc<SensorModel>>,
}

impl<'a> ModelNames<'a> {
    fn name_of(&mut self, model: &'a Arc<SensorModel>) -> String {
        let known = self
            .models
            .iter()
            .position(|m| Arc::ptr_eq(m, model) || ***m == **model);
        let index = known.unwrap_or_else(|| {
            self.models.push(model);
            self.models.len() - 1
        });
        format!("model-{index}")
    }
}

fn model_file(model: &SensorModel) -> ModelFile {
    let positive = |v: f64| (v > 0.0).then_some(Positive(v));
    ModelFile {
        kind: model.kind,
        unit: model.unit.clone(),
        table: model.table.rows().map(|r| r.map(Finite)).collect(),
        height: positive(model.height),
        footprint: positive(model.footprint),
    }
}

impl RobotProfile {
    /// The profile as the TOML text of a profile file; `from_toml` of it gives this profile
    /// back (its sensor models named `model-0`, `model-1`, ...).
    pub fn to_toml(&self) -> Result<String> {
        toml::to_string(&self.file()).map_err(|e| {
            Error::InvalidArgument(format!(
                "expected a profile that TOML can hold, found one it cannot: {e}"
            ))
        })
    }

    /// The profile as its file holds it.
    pub(super) fn file(&self) -> ProfileFile {
        let mut names = ModelNames { models: Vec::new() };
        let distance_sensors = self
            .distance_sensors
            .iter()
            .map(|s| SensorFile {
                name: s.name.clone(),
                position: s.position.map(Finite),
                heading: Some(Finite(s.heading)),
                elevation: (s.elevation != 0.0).then_some(Finite(s.elevation)),
                model: names.name_of(&s.model),
            })
            .collect();
        let ground_sensors = self
            .ground_sensors
            .iter()
            .map(|s| SensorFile {
                name: s.name.clone(),
                position: s.position.map(Finite),
                heading: None,
                elevation: None,
                model: names.name_of(&s.model),
            })
            .collect();
        let models: BTreeMap<String, ModelFile> = names
            .models
            .iter()
            .enumerate()
            .map(|(i, m)| (format!("model-{i}"), model_file(m)))
            .collect();
        ProfileFile {
            name: self.name.clone(),
            description: self.description.clone(),
            body_radius: Positive(self.body_radius),
            wheel_radius: Positive(self.wheel_radius),
            axle_length: Positive(self.axle_length),
            max_wheel_speed: Positive(self.max_wheel_speed),
            encoder_resolution: (self.encoder_resolution > 0.0)
                .then_some(Positive(self.encoder_resolution)),
            motor_gains: Some(self.motor_gains.map(Positive)),
            noise_scale: Some(NonNegative(self.noise_scale)),
            wall_reflectance: Some(Reflectance(self.wall_reflectance)),
            ground_gain: Some(Positive(self.ground_gain)),
            slip_on_contact: Some(SlipFraction(self.slip_on_contact)),
            models,
            distance_sensors,
            ground_sensors,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::{robot_profile_names, Perturbation};

    #[test]
    fn every_profile_reads_back_equal_from_its_text() {
        for name in robot_profile_names() {
            let profile = RobotProfile::builtin(&name).unwrap();
            let perturbed = profile
                .perturbed(&Perturbation {
                    wheel_radius_scale: 1.0 / 3.0,
                    motor_gains: [0.97, 1.01],
                    noise_scale: 2.5,
                    ir_angle_error: 0.07,
                    ir_offset_error: -0.001,
                    wall_reflectance: 0.3,
                    ground_gain: 0.9,
                    slip_on_contact: 0.2,
                    ..Default::default()
                })
                .unwrap();
            for p in [profile, perturbed] {
                let text = p.to_toml().unwrap();
                let back = RobotProfile::from_toml(&text, "<written>").unwrap();
                assert_eq!(format!("{back:?}"), format!("{p:?}"), "{name}:\n{text}");
            }
        }
    }
}
