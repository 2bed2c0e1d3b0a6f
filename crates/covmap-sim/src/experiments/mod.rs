//! The paper's experiments, reproduced in simulation.

mod fig3;
mod learn;

pub use fig3::{Fig3Config, Fig3Report, MapErrors, corridor_path, fig3, fig3_with};
pub use learn::{
    Drive, DriveScore, FACED_SCANS, LearnConfig, LearnReport, MAX_DRIVE_SCANS, WALL_BAND_M, learn,
    survey_drive,
};
