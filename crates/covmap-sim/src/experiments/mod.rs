//! The paper's experiments, reproduced in simulation.
