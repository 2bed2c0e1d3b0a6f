//! `covmap.World`: obstacle polygons, their ground truth and ray casts.

use std::path::PathBuf;

use covmap::sim::{ImageOptions, Material, Polygon, SimError, World};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::convert::{self, cell_array, rows_array};
use crate::errors::{Exception, OrRaise};
use crate::grid::PyGrid;
use crate::numbers::Float;

/// A set of obstacle polygons in the plane (metres); everything outside them
/// is free space, and overlapping polygons are their union.
///
/// ``polygons`` is a list of vertex arrays, each of shape ``(N, 2)`` (float64
/// numpy arrays or sequences of ``(x, y)``), in either orientation, closed or
/// not. ``materials`` (optional) gives each polygon's surface, ``"wall"``
/// (the default) or ``"glass"``, which decides how it echoes ultrasound. A
/// polygon that is not simple, has fewer than three distinct vertices or no
/// area raises ``InvalidPolygonError`` naming its index.
#[pyclass(frozen, name = "World", module = "covmap._native")]
pub(crate) struct PyWorld(pub(crate) World);

/// A material by its name.
fn material(py: Python<'_>, name: &str, index: usize) -> PyResult<Material> {
    Material::from_name(name).ok_or_else(|| {
        Exception::InvalidParameter.err(
            py,
            format!(
                "materials[{index}] must be \"wall\" or \"glass\", got {}",
                covmap::quoted(name)
            ),
        )
    })
}

/// The extension of `path`, lower-case, without the dot.
fn extension(path: &std::path::Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

/// A world from a file, by its extension (see `World.from_file`).
pub(crate) fn load(
    py: Python<'_>,
    path: PathBuf,
    wall_thickness_m: Option<Float>,
    resolution: Option<Float>,
    origin: Option<&Bound<'_, PyAny>>,
) -> PyResult<World> {
    let origin = origin
        .map(|o| convert::point(o, "origin", false))
        .transpose()?;
    let ext = extension(&path);
    let image = matches!(ext.as_str(), "pgm" | "png");
    let unused = [
        (
            "wall_thickness_m",
            wall_thickness_m.is_some() && ext != "map",
            "ARIA .map",
        ),
        (
            "resolution",
            resolution.is_some() && !image,
            ".pgm/.png image",
        ),
        ("origin", origin.is_some() && !image, ".pgm/.png image"),
    ];
    if let Some((name, _, format)) = unused.iter().find(|(_, given, _)| *given) {
        return Err(Exception::InvalidParameter.err(
            py,
            format!(
                "{}: {name} is an option of {format} worlds only; this file's format does not use it",
                path.display()
            ),
        ));
    }
    let resolution = resolution.map(|r| r.0);
    if image && resolution.is_none() {
        return Err(Exception::InvalidParameter.err(
            py,
            format!(
                "{}: an occupancy image needs resolution= (metres per pixel)",
                path.display()
            ),
        ));
    }
    let loaded = py.detach(|| match ext.as_str() {
        "json" | "geojson" => World::from_geojson_file(&path),
        "map" => World::from_aria_map_file(&path, wall_thickness_m.map_or(0.1, |w| w.0)),
        "yaml" | "yml" => World::from_ros_map_yaml(&path),
        "pgm" | "png" => {
            let options = ImageOptions {
                origin_m: origin.unwrap_or([0.0, 0.0]),
                ..ImageOptions::new(resolution.unwrap_or(f64::NAN))
            };
            World::from_image_file(&path, &options)
        }
        _ => Err(SimError::Parse {
            path: path.clone(),
            place: "file name".into(),
            reason: format!(
                "unknown extension {ext:?}: expected .json/.geojson (GeoJSON), .map (ARIA), \
                 .yaml (ROS map_server) or .pgm/.png (occupancy image)"
            ),
        }),
    });
    loaded.or_raise(py)
}

#[pymethods]
impl PyWorld {
    #[new]
    #[pyo3(signature = (polygons, materials=None))]
    fn new(
        py: Python<'_>,
        polygons: &Bound<'_, PyAny>,
        materials: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let not_polygons = || {
            Exception::InvalidType.err(
                py,
                format!(
                    "polygons must be a list of (N, 2) vertex arrays, got {}",
                    polygons.get_type()
                ),
            )
        };
        let lists = convert::items(polygons, "polygons", convert::MAX_VALUES, &not_polygons)?;
        // No more names read than there are polygons (pyo3 would reserve
        // what a sequence's len() claims).
        let materials = materials
            .map(|m| {
                let not_names = || {
                    Exception::InvalidType.err(
                        py,
                        format!(
                            "materials must be a list of names, one per polygon, got {}",
                            m.get_type()
                        ),
                    )
                };
                if let Ok(n) = m.len()
                    && n != lists.len()
                    && !m.is_instance_of::<pyo3::types::PyString>()
                {
                    return Err(SimError::LengthMismatch {
                        what: "materials and polygons",
                        left: n,
                        right: lists.len(),
                    })
                    .or_raise(py);
                }
                let names = convert::items(m, "materials", lists.len(), &not_names)?;
                names
                    .iter()
                    .map(|n| n.extract::<String>().map_err(|_| not_names()))
                    .collect::<PyResult<Vec<String>>>()
            })
            .transpose()?;
        let materials = match materials {
            None => vec![Material::Wall; lists.len()],
            Some(names) if names.len() == lists.len() => names
                .iter()
                .enumerate()
                .map(|(i, n)| material(py, n, i))
                .collect::<PyResult<_>>()?,
            Some(names) => {
                return Err(SimError::LengthMismatch {
                    what: "materials and polygons",
                    left: names.len(),
                    right: lists.len(),
                })
                .or_raise(py);
            }
        };
        let mut vertex_lists = Vec::with_capacity(lists.len());
        for (i, list) in lists.iter().enumerate() {
            vertex_lists.push(convert::rows::<2>(
                list,
                &format!("polygons[{i}]"),
                "vertex (x, y)",
            )?);
        }
        let built = py.detach(|| {
            vertex_lists
                .into_iter()
                .zip(materials)
                .enumerate()
                .map(|(index, (v, m))| {
                    Polygon::new(v, m).map_err(|e| match e {
                        SimError::InvalidPolygon { reason, .. } => {
                            SimError::InvalidPolygon { index, reason }
                        }
                        other => other,
                    })
                })
                .collect::<covmap::sim::Result<Vec<_>>>()
                .map(World::new)
        });
        built.map(Self).or_raise(py)
    }

    /// A built-in world by name (see ``World.builtin_names()``): ``"corridor"``
    /// (the paper's Fig. 3), ``"office"``, ``"partial"`` (Fig. 1). An unknown
    /// name raises ``UnknownWorldError``.
    #[staticmethod]
    fn builtin(py: Python<'_>, name: &str) -> PyResult<Self> {
        World::builtin(name).map(Self).or_raise(py)
    }

    /// The names of the built-in worlds.
    #[staticmethod]
    fn builtin_names() -> Vec<&'static str> {
        World::builtin_names().to_vec()
    }

    /// A world from a file, by its extension:
    ///
    /// - ``.json``, ``.geojson``: GeoJSON polygons in metres (a feature's
    ///   ``properties.material`` is ``"wall"`` or ``"glass"``);
    /// - ``.map``: the ``LINES`` of an ARIA map, each a wall
    ///   ``wall_thickness_m`` thick (default 0.1 m);
    /// - ``.yaml``, ``.yml``: a ROS map_server YAML file and its image;
    /// - ``.pgm``, ``.png``: an occupancy image (dark = occupied) of
    ///   ``resolution`` metres per pixel, its lower-left corner at ``origin``
    ///   (default ``(0, 0)``); ``resolution`` is required.
    ///
    /// In an image, the pixels that are not free (occupancy below the
    /// YAML's ``free_thresh``, default 0.196) are obstacles: the occupied
    /// ones and the unknown grey ones, so that a robot never drives in
    /// space the map did not see; a map_server file in ``mode: scale``
    /// makes obstacles of the occupied pixels only.
    ///
    /// An option the file's format does not use (``resolution`` for a
    /// GeoJSON file, say) raises ``InvalidParameterError``: it would be
    /// ignored. A malformed file raises ``FileFormatError`` (a ``ValueError``) naming
    /// the file and the place; a file that cannot be read raises
    /// ``FileIOError`` (an ``OSError``).
    #[staticmethod]
    #[pyo3(signature = (path, *, wall_thickness_m=None, resolution=None, origin=None))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        wall_thickness_m: Option<Float>,
        resolution: Option<Float>,
        origin: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        load(py, path, wall_thickness_m, resolution, origin).map(Self)
    }

    /// Pickle and copy support: rebuilt by ``World._from_geojson`` from
    /// ``to_geojson()``.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let rebuild = py.get_type::<Self>().getattr("_from_geojson")?;
        Ok((rebuild, (self.0.to_geojson(),)))
    }
    /// Unpickling support: the world of a GeoJSON text (``to_geojson``).
    #[staticmethod]
    fn _from_geojson(py: Python<'_>, text: &str) -> PyResult<Self> {
        World::from_geojson_str(text, "pickled world")
            .map(Self)
            .or_raise(py)
    }

    /// The world as GeoJSON text (``World.from_file`` reads it back from a
    /// ``.geojson`` file).
    fn to_geojson(&self) -> String {
        self.0.to_geojson()
    }

    /// ``(x_min, y_min, x_max, y_max)`` of all obstacles, metres (all zero when
    /// there are none).
    #[getter]
    fn bounds(&self) -> convert::Rectangle {
        convert::rectangle(self.0.bounds_m())
    }
    /// The exterior ring of each polygon: a list of float64 ``(N, 2)`` arrays.
    #[getter]
    fn polygons<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.0
            .polygons()
            .iter()
            .map(|p| rows_array(py, p.exterior()))
            .collect()
    }
    /// The holes of each polygon: a list (one per polygon) of lists of
    /// float64 ``(K, 2)`` arrays.
    #[getter]
    fn holes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let per_polygon = self
            .0
            .polygons()
            .iter()
            .map(|p| {
                p.holes()
                    .iter()
                    .map(|h| rows_array(py, h))
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>();
        PyList::new(py, per_polygon)
    }
    /// The material of each polygon, ``"wall"`` or ``"glass"``.
    #[getter]
    fn materials(&self) -> Vec<&'static str> {
        self.0
            .polygons()
            .iter()
            .map(|p| p.material().as_str())
            .collect()
    }
    /// The sum of the polygons' areas, square metres (overlaps counted twice;
    /// the union is ``coverage(grid).sum()`` times the cell area).
    #[getter]
    fn polygon_area_m2(&self) -> f64 {
        self.0.polygon_area_m2()
    }
    fn __len__(&self) -> usize {
        self.0.len()
    }

    /// The exact fraction of every cell of ``grid`` inside the obstacles:
    /// float64, ``(rows, cols)``, in ``[0, 1]`` (the ground truth a coverage
    /// map estimates). Runs with the GIL released.
    fn coverage<'py>(
        &self,
        py: Python<'py>,
        grid: Bound<'py, PyGrid>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let grid = grid.get().0;
        let world = &self.0;
        let values = py.detach(|| world.try_coverage(&grid)).or_raise(py)?;
        cell_array(py, &grid, values)
    }

    /// Cast rays from ``origins`` along ``angles`` (radians, counter-clockwise
    /// from +x) up to ``max_range_m``: the distance to the first surface of
    /// each, float64 ``(N,)``, ``max_range_m`` where nothing was hit.
    ///
    /// ``origins`` is a float64 array of shape ``(N, 2)`` (or one point
    /// ``(x, y)`` shared by every ray), ``angles`` a float64 array of shape
    /// ``(N,)``. With ``return_incidence=True`` the result is a pair
    /// ``(distances, incidence)``, ``incidence`` the angle between each ray and
    /// the surface normal in ``[0, pi/2]`` (NaN where nothing was hit).
    #[pyo3(signature = (origins, angles, max_range_m, *, return_incidence=false))]
    fn cast<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        angles: &Bound<'py, PyAny>,
        max_range_m: Float,
        return_incidence: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let angles = convert::readings(angles, "angles", convert::MAX_VALUES)?;
        let single = match origins.cast::<numpy::PyUntypedArray>() {
            Ok(a) => numpy::PyUntypedArrayMethods::ndim(a) == 1,
            Err(_) => origins.extract::<[f64; 2]>().is_ok(),
        };
        let origins = if single {
            let p = convert::readings(origins, "origins", convert::MAX_VALUES)?;
            let Ok(p) = <[f64; 2]>::try_from(p.as_slice()) else {
                return Err(Exception::ArrayShape.err(
                    py,
                    format!("origins must have shape (N, 2) or (2,), got ({},)", p.len()),
                ));
            };
            vec![p; angles.len()]
        } else {
            convert::rows::<2>(origins, "origins", "point (x, y)")?
        };
        let world = &self.0;
        let hits = py
            .detach(|| world.cast_batch(&origins, &angles, max_range_m.0))
            .or_raise(py)?;
        let distances = PyArray1::from_iter(py, hits.iter().map(|h| h.distance_m));
        if return_incidence {
            let incidence = PyArray1::from_iter(py, hits.iter().map(|h| h.incidence_rad));
            Ok(PyTuple::new(py, [distances.into_any(), incidence.into_any()])?.into_any())
        } else {
            Ok(distances.into_any())
        }
    }

    /// Whether the point ``(x, y)`` lies inside an obstacle.
    fn contains(&self, x: Float, y: Float) -> bool {
        self.0.contains_point([x.0, y.0])
    }
    /// Distance from ``(x, y)`` to the nearest obstacle, metres: 0 inside
    /// one, infinite in an empty world. A coordinate that is not finite
    /// raises ``InvalidValueError``.
    fn distance_to_obstacle(&self, py: Python<'_>, x: Float, y: Float) -> PyResult<f64> {
        let point = [x.0, y.0];
        convert::finite_points(py, &[point], "(x, y)")?;
        Ok(self.0.distance_to_obstacle_m(point))
    }

    fn __repr__(&self) -> String {
        let [a, b, c, d] = self.0.bounds_m();
        format!(
            "<World: {} polygons within ({a:?}, {b:?}, {c:?}, {d:?})>",
            self.0.len()
        )
    }
}
