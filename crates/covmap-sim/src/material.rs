//! What a surface is made of, which decides how it echoes.

use serde::{Deserialize, Serialize};

/// The material of an obstacle's surface.
///
/// Both reflect a laser. For ultrasound they differ in the critical angle of
/// incidence beyond which the echo is reflected away (specular reflection) and
/// lost: walls scatter enough to echo at fairly oblique incidence, glass echoes
/// only near normal incidence (see [`crate::SonarRing`]).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "lowercase")]
#[repr(u8)]
pub enum Material {
    /// Plaster, brick, wood, furniture: a rough surface.
    #[default]
    Wall = 0,
    /// A smooth pane: echoes sonar only near normal incidence.
    Glass = 1,
}

impl Material {
    /// Every material, in code order.
    pub const ALL: [Material; 2] = [Material::Wall, Material::Glass];

    /// The lowercase name used in files (`"wall"`, `"glass"`).
    pub fn as_str(self) -> &'static str {
        match self {
            Material::Wall => "wall",
            Material::Glass => "glass",
        }
    }

    /// The material of a lowercase name, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.as_str() == name)
    }

    /// A small integer code (`Wall` = 0, `Glass` = 1), stable for array outputs.
    pub fn code(self) -> u8 {
        self as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for m in Material::ALL {
            assert_eq!(Material::from_name(m.as_str()), Some(m));
        }
        assert_eq!(Material::from_name("Glass"), None);
        assert_eq!(Material::Glass.code(), 1);
    }
}
