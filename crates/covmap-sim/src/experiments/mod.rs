//! The paper's experiments, reproduced in simulation.

mod fig3;

pub use fig3::{Fig3Config, Fig3Report, MapErrors, corridor_path, fig3, fig3_with};
