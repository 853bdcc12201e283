//! Animated scenes: a trajectory of any model drawn in the browser, from one
//! self-contained HTML file (inline script and canvas, no network).
//!
//! A [`Scene`] is built from the model alone ([`Scene::of`] a generated
//! system, which carries its model, or [`Scene::new`] from its text): its named
//! points, joined by a segment wherever one is located from another
//! (`point P = Q ± vec`, joint points), its bodies drawn as links between
//! the moving named points fixed in them (a robot's joint origins: each link
//! from its joint to its children's) or, with fewer than two such points or
//! a size given, as boxes at their centres, turned with their frames and
//! sized from their inertia, and its particles drawn as dots. The view fits
//! what is drawn over the whole motion; point names are written beside the
//! points when there are few, and shown under the mouse otherwise. Nothing
//! of this enters the equations. The builder's methods add segments and set
//! body sizes by name. [`Scene::write`] writes a [`Recording`] (times,
//! coordinates, energies) as an animation: play and pause, a time slider,
//! the playback speed, a 2-D view when all motion stays in one plane and an
//! orthographic 3-D view turned by dragging the mouse otherwise, the energy
//! error under it (for a driven system, whose recording carries the inputs'
//! power: the energy change beside the inputs' work) and the model's
//! equations in a collapsible panel. Long
//! recordings are decimated uniformly in time for display, never truncated.
//!
//! Positions come from one place, [`Kinematics`]: today the engine's own
//! kinematics, evaluated by [`dalembert_codegen::Geometry`].

use std::fmt::{self, Write as _};
use std::path::{Path, PathBuf};

use dalembert_codegen::{Geometry, Values};

/// The page the data is embedded in.
const TEMPLATE: &str = include_str!("scene.html");
/// Where in [`TEMPLATE`] the data goes.
const DATA_SLOT: &str = "/*DATA*/null";
/// The most frames a page holds, whatever the recording's length.
const MAX_FRAMES: usize = 2000;
/// The numbers a page's frames may hold together (about 7 bytes each): long
/// recordings of large systems keep fewer frames, which the page
/// interpolates.
const NUMBER_BUDGET: usize = 450_000;
/// The fewest frames a page keeps when the recording has them.
const MIN_FRAMES: usize = 200;
/// Significant digits of displayed positions, relative to the scene's size.
const DIGITS: i32 = 5;
/// A coordinate or a body-fixed offset that varies less than this fraction
/// of the scene's size counts as constant.
const STILL: f64 = 1e-9;
/// A body's thickness across a dimension its size leaves open, as a
/// fraction of its largest size.
const THICKNESS: f64 = 0.12;
/// The size of a body nothing sizes, as a fraction of the scene's size.
const LONE_BODY: f64 = 0.05;

/// A scene could not be built or written.
#[derive(Debug)]
pub struct SceneError(String);

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}

fn error<T>(message: impl Into<String>) -> Result<T, SceneError> {
    Err(SceneError(message.into()))
}

/// A trajectory to animate: times, coordinates and total energies, one
/// sample per step, and for a driven system the work its inputs did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recording {
    t: Vec<f64>,
    q: Vec<Vec<f64>>,
    energy: Vec<f64>,
    /// The inputs' power and their work since the first sample, when the
    /// samples were pushed with [`Recording::push_driven`].
    driven: Vec<(f64, f64)>,
}

impl Recording {
    /// An empty recording.
    pub fn new() -> Recording {
        Recording::default()
    }

    /// Adds the sample at time `t` (after the previous one) with
    /// coordinates `q` and total energy `energy`.
    pub fn push(&mut self, t: f64, q: &[f64], energy: f64) {
        self.t.push(t);
        self.q.push(q.to_vec());
        self.energy.push(energy);
    }

    /// Adds a sample of a driven system: as [`push`](Recording::push),
    /// with the power `power` its inputs deliver at `t` ([`input_power`]).
    /// The recording integrates the power (trapezoidal rule) into the
    /// inputs' work, which the page draws beside the energy change: for a
    /// driven system the energy changes by the inputs' work, and only
    /// their difference is the integrator's error.
    pub fn push_driven(&mut self, t: f64, q: &[f64], energy: f64, power: f64) {
        let work = match (self.t.last(), self.driven.last()) {
            (Some(&t0), Some(&(p0, w0))) => w0 + (t - t0) * (p0 + power) / 2.0,
            _ => 0.0,
        };
        self.push(t, q, energy);
        self.driven.push((power, work));
    }

    /// Whether the samples carry the inputs' power (all were pushed with
    /// [`push_driven`](Recording::push_driven)).
    pub fn is_driven(&self) -> bool {
        !self.t.is_empty() && self.driven.len() == self.t.len()
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The sample times.
    pub fn times(&self) -> &[f64] {
        &self.t
    }
}

/// Where the drawn parts of a system are at one instant, in `N`'s axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// The named points, `O` first.
    pub points: Vec<[f64; 3]>,
    /// The bodies' centres.
    pub centres: Vec<[f64; 3]>,
    /// The bodies' rotation matrices (columns: the body frame's unit
    /// vectors).
    pub rotations: Vec<[[f64; 3]; 3]>,
    /// The particles.
    pub particles: Vec<[f64; 3]>,
}

/// What a system is made of, by name.
#[derive(Clone, Debug, PartialEq)]
struct Layout {
    points: Vec<String>,
    segments: Vec<(usize, usize)>,
    bodies: Vec<String>,
    particles: Vec<String>,
    /// Each body's mass and central inertia.
    mass_properties: Vec<(f64, [[f64; 3]; 3])>,
}

/// Where everything is at `(t, q)`.
type PoseAt = Box<dyn Fn(f64, &[f64]) -> Pose>;

/// The kept samples' indices and their times and poses.
type KeptPoses = (Vec<usize>, Vec<(f64, Pose)>);

/// The source of positions: the one thing to change when the generator
/// emits kinematic outputs.
struct Kinematics {
    layout: Layout,
    pose: PoseAt,
    name: String,
    nq: usize,
}

/// The engine's kinematics of the system in `source` with `parameters`:
/// the same expressions its equations are derived from, evaluated by
/// [`Geometry`].
fn engine_kinematics(source: &str, parameters: &[f64]) -> Result<Kinematics, SceneError> {
    let geometry =
        Geometry::new(source).map_err(|e| SceneError(format!("cannot read the model: {e}")))?;
    if parameters.len() != geometry.np() {
        return error(format!(
            "the model has {} parameters, {} values were given",
            geometry.np(),
            parameters.len()
        ));
    }
    let parameters = parameters.to_vec();
    let mass_properties = geometry.mass_properties(&at(&parameters, 0.0, &[]));
    let layout = Layout {
        points: geometry.points().to_vec(),
        segments: geometry.segments().to_vec(),
        bodies: geometry.bodies().to_vec(),
        particles: geometry.particles().to_vec(),
        mass_properties,
    };
    let (nq, named, bodies) = (geometry.nq(), layout.points.len(), layout.bodies.len());
    let name = geometry.name().to_string();
    let pose = move |t: f64, q: &[f64]| {
        let at = at(&parameters, t, q);
        let mut positions = geometry.positions(&at);
        let particles = positions.split_off(named + bodies);
        let centres = positions.split_off(named);
        let mut rotations = geometry.rotations(&at);
        let rotations = rotations.split_off(rotations.len() - bodies);
        Pose {
            points: positions,
            centres,
            rotations,
            particles,
        }
    };
    Ok(Kinematics {
        layout,
        pose: Box::new(pose),
        name,
        nq,
    })
}

/// The values geometry reads: parameters, `t` and `q` (no speed or input).
fn at<'a>(parameters: &'a [f64], t: f64, q: &'a [f64]) -> Values<'a> {
    Values {
        parameters,
        t,
        q,
        qd: &[],
        u: &[],
    }
}

/// The text of the equations panel.
enum Equations {
    /// Given by the caller.
    Given(String),
    /// To derive from this model text when a page is written.
    Derived(String),
}

impl Equations {
    fn text(&self) -> Result<String, SceneError> {
        match self {
            Equations::Given(text) => Ok(text.clone()),
            Equations::Derived(source) => {
                dalembert_codegen::equations(source, dalembert_codegen::Style::Unicode)
                    .map_err(|e| SceneError(format!("cannot derive the equations: {e}")))
            }
        }
    }
}

/// An animated scene of one system: what to draw and how.
pub struct Scene {
    kinematics: Kinematics,
    title: String,
    equations: Equations,
    sizes: Vec<Option<[f64; 3]>>,
    max_frames: usize,
}

impl Scene {
    /// The scene of a generated system, from the model it carries (its
    /// text and its parameters' values: [`dalembert::Model`]), so that
    /// nothing is pasted and nothing can drift from the compiled system.
    /// The equations panel shows the derived equations; the title is the
    /// system's name.
    pub fn of<S: dalembert::Model<NP>, const NP: usize>(system: &S) -> Result<Scene, SceneError> {
        Scene::new(S::SOURCE, &system.parameter_values())
    }

    /// The scene of the system in `source` (the model's text, in the
    /// language of `dalembert!`) with its parameters' values in declaration
    /// order. The equations panel shows the derived equations; the title is
    /// the system's name.
    pub fn new(source: &str, parameters: &[f64]) -> Result<Scene, SceneError> {
        let kinematics = engine_kinematics(source, parameters)?;
        let equations = Equations::Derived(source.to_string());
        let title = kinematics.name.clone();
        let sizes = vec![None; kinematics.layout.bodies.len()];
        Ok(Scene {
            kinematics,
            title,
            equations,
            sizes,
            max_frames: MAX_FRAMES,
        })
    }

    /// Sets the title shown above the animation.
    pub fn title(mut self, title: &str) -> Scene {
        self.title = title.to_string();
        self
    }

    /// Sets the text of the equations panel (a generated system's
    /// `EQUATIONS`).
    pub fn equations(mut self, text: &str) -> Scene {
        self.equations = Equations::Given(text.to_string());
        self
    }

    /// Also joins named points `from` and `to` by a segment.
    pub fn segment(mut self, from: &str, to: &str) -> Result<Scene, SceneError> {
        let segment = (self.point(from)?, self.point(to)?);
        self.kinematics.layout.segments.push(segment);
        Ok(self)
    }

    /// Draws body `body` as a box of `size` (full lengths along its frame's
    /// x, y and z; a zero gets a thickness) instead of the size its inertia
    /// or the points fixed in it suggest.
    pub fn body_size(mut self, body: &str, size: [f64; 3]) -> Result<Scene, SceneError> {
        let layout = &self.kinematics.layout;
        let Some(i) = layout.bodies.iter().position(|b| b == body) else {
            return error(format!(
                "no body `{body}`; the bodies are {:?}",
                layout.bodies
            ));
        };
        self.sizes[i] = Some(size);
        Ok(self)
    }

    /// Keeps at most `frames` frames (at least 2) of a recording.
    pub fn max_frames(mut self, frames: usize) -> Scene {
        self.max_frames = frames.max(2);
        self
    }

    fn point(&self, name: &str) -> Result<usize, SceneError> {
        let points = &self.kinematics.layout.points;
        match points.iter().position(|p| p == name) {
            Some(i) => Ok(i),
            None => error(format!(
                "no point `{name}`; the named points are {points:?}"
            )),
        }
    }

    /// The indices of the samples of `recording` a page keeps.
    pub fn kept_frames(&self, recording: &Recording) -> Vec<usize> {
        let layout = &self.kinematics.layout;
        let per_frame =
            3 * (layout.points.len() + layout.particles.len()) + 7 * layout.bodies.len() + 2;
        let budget = (NUMBER_BUDGET / per_frame.max(1)).max(MIN_FRAMES);
        decimate(recording.times(), budget.min(self.max_frames))
    }

    /// The poses drawn: the kept samples' times and where everything is.
    pub fn poses(&self, recording: &Recording) -> Result<Vec<(f64, Pose)>, SceneError> {
        Ok(self.kept_poses(recording)?.1)
    }

    /// The page showing `recording`.
    pub fn html(&self, recording: &Recording) -> Result<String, SceneError> {
        if recording.is_empty() {
            return error("the recording has no sample");
        }
        let (kept, poses) = self.kept_poses(recording)?;
        let e0 = recording.energy[0];
        let energy_change: Vec<f64> = kept.iter().map(|&i| recording.energy[i] - e0).collect();
        // A driven run: the inputs' work at the kept samples, and the
        // energy error `E − E(0) − W` over all samples, from the full
        // numbers (the drawn ones keep five digits).
        let driven = recording.is_driven().then(|| {
            let work: Vec<f64> = kept.iter().map(|&i| recording.driven[i].1).collect();
            let error = (0..recording.len())
                .map(|i| (recording.energy[i] - e0 - recording.driven[i].1).abs())
                .fold(0.0_f64, f64::max);
            (work, error)
        });
        let driven = driven
            .as_ref()
            .map(|(work, error)| (work.as_slice(), *error));
        let data = self.data(&poses, &energy_change, driven)?;
        Ok(TEMPLATE.replacen(DATA_SLOT, &data, 1))
    }

    /// The indices of the kept samples and their poses.
    fn kept_poses(&self, recording: &Recording) -> Result<KeptPoses, SceneError> {
        if let Some(q) = recording.q.iter().find(|q| q.len() != self.kinematics.nq) {
            return error(format!(
                "the model has {} coordinates, a sample has {}",
                self.kinematics.nq,
                q.len()
            ));
        }
        let kept = self.kept_frames(recording);
        let poses = kept
            .iter()
            .map(|&i| {
                let (t, q) = (recording.t[i], &recording.q[i]);
                (t, (self.kinematics.pose)(t, q))
            })
            .collect();
        Ok((kept, poses))
    }

    /// Writes the page showing `recording` to `path`.
    pub fn write(
        &self,
        path: impl AsRef<Path>,
        recording: &Recording,
    ) -> Result<PathBuf, SceneError> {
        let path = path.as_ref();
        let html = self.html(recording)?;
        std::fs::write(path, html)
            .map_err(|e| SceneError(format!("cannot write {}: {e}", path.display())))?;
        Ok(path.to_path_buf())
    }

    /// The page's data as compact JSON: `energy` is `E(t) − E(0)` at the
    /// kept samples; for a driven system, `driven` is the inputs' work
    /// there and the largest `|E − E(0) − W|`.
    fn data(
        &self,
        poses: &[(f64, Pose)],
        energy: &[f64],
        driven: Option<(&[f64], f64)>,
    ) -> Result<String, SceneError> {
        let layout = &self.kinematics.layout;
        let scene = Extent::of(poses, &[]).size;
        let links = self.links(poses, scene);
        let sizes = self.body_sizes(poses, scene);
        // A body drawn as links is not drawn as a box: its box does not
        // count in the view.
        let boxes: Vec<[f64; 3]> = sizes
            .iter()
            .enumerate()
            .map(|(b, &size)| match links.iter().any(|l| l.0 == b) {
                true => [0.0; 3],
                false => size,
            })
            .collect();
        let extent = Extent::of(poses, &boxes);
        let decimals = (DIGITS - 1 - extent.size.log10().floor() as i32).max(0) as usize;
        let number = |x: f64| rounded(x, decimals);
        let mut json = String::from("{");
        let mut field = |name: &str, value: String| {
            if json.len() > 1 {
                json.push(',');
            }
            let _ = write!(json, "{}:{value}", string(name));
        };
        field("title", string(&self.title));
        field("equations", string(&self.equations.text()?));
        field("points", list(layout.points.iter().map(|p| string(p))));
        field("bodies", list(layout.bodies.iter().map(|b| string(b))));
        field(
            "particles",
            list(layout.particles.iter().map(|p| string(p))),
        );
        field(
            "segments",
            list(layout.segments.iter().map(|(i, j)| format!("[{i},{j}]"))),
        );
        field(
            "sizes",
            list(sizes.iter().map(|s| list(s.iter().map(|&x| number(x))))),
        );
        field(
            "links",
            list(links.iter().map(|(b, i, j)| format!("[{b},{i},{j}]"))),
        );
        field(
            "normal",
            extent.normal.map_or("null".into(), |k| k.to_string()),
        );
        field("center", list(extent.center.iter().map(|&x| number(x))));
        field("size", number(extent.size));
        field("radius", number(extent.radius));
        field(
            "t",
            list(poses.iter().map(|(t, _)| rounded_significant(*t))),
        );
        let series = |values: &[f64]| list(values.iter().map(|&e| rounded_significant(e)));
        field("energy", series(energy));
        field(
            "work",
            driven.map_or("null".into(), |(work, _)| series(work)),
        );
        field(
            "error",
            driven.map_or("null".into(), |(_, error)| rounded_significant(error)),
        );
        field(
            "frames",
            list(poses.iter().map(|(_, pose)| {
                let quaternions = pose.rotations.iter().map(quaternion);
                let bodies = pose.centres.iter().zip(quaternions);
                let numbers = pose
                    .points
                    .iter()
                    .flatten()
                    .map(|&x| number(x))
                    .chain(bodies.flat_map(|(c, q)| {
                        let centre = c.iter().map(|&x| number(x));
                        centre.chain(q.map(|x| rounded(x, 4)))
                    }))
                    .chain(pose.particles.iter().flatten().map(|&x| number(x)));
                list(numbers)
            })),
        );
        json.push('}');
        Ok(json)
    }

    /// The links drawn for the bodies of a robot: `(body, from, to)`, the
    /// segments between named points (a joint's point and the point it is
    /// placed from: the parent link's joint origin) that lie in one such
    /// body, the first declared: a robot's link
    /// ([`is_robot_link`](Scene::is_robot_link)), both ends fixed in it and
    /// apart. Bodies with an idealised inertia keep their boxes. None when
    /// nothing moves.
    fn links(&self, poses: &[(f64, Pose)], scene: f64) -> Vec<(usize, usize, usize)> {
        let near =
            |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() <= STILL * scene);
        // Without motion every point would count as fixed in every body.
        let still = poses.iter().all(|(_, pose)| {
            let first = &poses[0].1.points;
            pose.points.iter().zip(first).all(|(a, b)| near(a, b))
        });
        if still {
            return Vec::new();
        }
        let layout = &self.kinematics.layout;
        let fixed: Vec<Vec<(usize, [f64; 3])>> = (0..self.sizes.len())
            .map(|b| match self.is_robot_link(poses, b, scene) {
                true => fixed_points(poses, b, scene),
                false => Vec::new(),
            })
            .collect();
        let at = |b: usize, p: usize| fixed[b].iter().find(|(q, _)| *q == p).map(|(_, at)| at);
        layout
            .segments
            .iter()
            .filter_map(|&(i, j)| {
                let body = (0..fixed.len()).find(|&b| match (at(b, i), at(b, j)) {
                    (Some(a), Some(c)) => !near(a, c),
                    _ => false,
                })?;
                Some((body, i, j))
            })
            .collect()
    }

    /// Whether body `b` is a robot's link: no size given, a full inertia
    /// (an imported link's, whose box of equal inertia says little of its
    /// shape: a URDF's placeholder inertia makes metre-wide boxes) and named
    /// points fixed in it apart (its joint origin and its children's).
    fn is_robot_link(&self, poses: &[(f64, Pose)], b: usize, scene: f64) -> bool {
        let layout = &self.kinematics.layout;
        let full_inertia = inertia_box(layout.mass_properties[b])
            .is_some_and(|size| size.iter().all(|&x| x > 0.0));
        self.sizes[b].is_none()
            && full_inertia
            && fixed_point_span(poses, b, scene)
                .iter()
                .any(|&x| x > STILL * scene)
    }

    /// Each body's drawn size: given, else its uniform box of equal
    /// inertia, else the span of the named points fixed in it; open
    /// dimensions get a thickness. A robot's link is sized from its points.
    fn body_sizes(&self, poses: &[(f64, Pose)], scene: f64) -> Vec<[f64; 3]> {
        let layout = &self.kinematics.layout;
        (0..layout.bodies.len())
            .map(|b| {
                let size = self.sizes[b]
                    .or_else(|| match self.is_robot_link(poses, b, scene) {
                        true => None,
                        false => inertia_box(layout.mass_properties[b]),
                    })
                    .unwrap_or_else(|| fixed_point_span(poses, b, scene));
                thicken(size, scene)
            })
            .collect()
    }
}

/// The power the inputs `u` deliver to `system` at `(t, q, v)`: the
/// generalized forces they add, `f(t, q, v, u) − f(t, q, v, 0)`, times the
/// speeds. What [`Recording::push_driven`] integrates into their work.
pub fn input_power<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> f64
where
    S: dalembert::MultibodySystem<NQ, NV, NU>,
{
    let driven = system.forcing(t, q, v, u);
    let free = system.forcing(t, q, v, &[0.0; NU]);
    (0..NV).map(|k| (driven[k] - free[k]) * v[k]).sum()
}

/// The full lengths of the uniform box with the body's mass and principal
/// moments (read from the diagonal), if the moments make one and it is not
/// a point: `a² = 6 (I_yy + I_zz − I_xx) / m` and so on.
fn inertia_box((mass, inertia): (f64, [[f64; 3]; 3])) -> Option<[f64; 3]> {
    if mass <= 0.0 {
        return None;
    }
    let moment = |i: usize| inertia[i][i];
    let squares =
        [0, 1, 2].map(|i| 6.0 * (moment((i + 1) % 3) + moment((i + 2) % 3) - moment(i)) / mass);
    let scale = squares.iter().fold(0.0_f64, |a, &s| a.max(s.abs()));
    let tolerance = 1e-12 * scale;
    if scale == 0.0 || squares.iter().any(|&s| s < -tolerance) {
        return None;
    }
    Some(squares.map(|s| s.max(0.0).sqrt()))
}

/// Twice the largest distance, along each of the body's axes, of the named
/// points that stay fixed in body `b` over the drawn poses.
fn fixed_point_span(poses: &[(f64, Pose)], b: usize, scene: f64) -> [f64; 3] {
    fixed_points(poses, b, scene)
        .into_iter()
        .fold([0.0_f64; 3], |span, (_, at)| {
            [0, 1, 2].map(|i| span[i].max(2.0 * at[i].abs()))
        })
}

/// The named points that stay fixed in body `b` over the drawn poses, in
/// declaration order, with where each is in the body's axes from its
/// centre.
fn fixed_points(poses: &[(f64, Pose)], b: usize, scene: f64) -> Vec<(usize, [f64; 3])> {
    let in_body = |pose: &Pose, p: usize| {
        let (r, c, x) = (&pose.rotations[b], &pose.centres[b], &pose.points[p]);
        let d = [0, 1, 2].map(|i| x[i] - c[i]);
        [0, 1, 2].map(|j| (0..3).map(|i| r[i][j] * d[i]).sum::<f64>())
    };
    let Some((_, first)) = poses.first() else {
        return Vec::new();
    };
    (0..first.points.len())
        .map(|p| (p, in_body(first, p)))
        .filter(|&(p, start)| {
            poses.iter().all(|(_, pose)| {
                let now = in_body(pose, p);
                (0..3).all(|i| (now[i] - start[i]).abs() <= STILL * scene)
            })
        })
        .collect()
}

/// `size` with every zero dimension given a thickness, and a body with no
/// size at all given one from the scene's.
fn thicken(size: [f64; 3], scene: f64) -> [f64; 3] {
    let largest = size.iter().fold(0.0_f64, |a, &s| a.max(s));
    if largest == 0.0 {
        return [LONE_BODY * scene; 3];
    }
    size.map(|s| s.max(THICKNESS * largest))
}

/// The region the motion covers, and its plane if it keeps to one.
struct Extent {
    center: [f64; 3],
    size: f64,
    /// The farthest any part comes from the centre: the 3-D view, turned
    /// any way, fits a circle of this radius.
    radius: f64,
    /// The `N` axis (0, 1, 2) normal to the plane of all motion.
    normal: Option<usize>,
}

impl Extent {
    /// The region covered by the parts of `poses` with bodies of full
    /// lengths `sizes` (none: points only), and the plane of the motion.
    fn of(poses: &[(f64, Pose)], sizes: &[[f64; 3]]) -> Extent {
        let parts = || {
            poses.iter().flat_map(|(_, pose)| {
                pose.points
                    .iter()
                    .chain(&pose.centres)
                    .chain(&pose.particles)
                    .copied()
            })
        };
        let corners = || {
            poses.iter().flat_map(|(_, pose)| {
                pose.centres
                    .iter()
                    .zip(&pose.rotations)
                    .zip(sizes)
                    .flat_map(|((c, r), size)| {
                        (0..8).map(move |corner: usize| {
                            let sign =
                                |axis: usize| if corner >> axis & 1 == 1 { 0.5 } else { -0.5 };
                            [0, 1, 2].map(|i| {
                                c[i] + (0..3).map(|j| r[i][j] * sign(j) * size[j]).sum::<f64>()
                            })
                        })
                    })
            })
        };
        let all = Bounds::of(parts().chain(corners()));
        let (size, center) = (all.size(), all.center());
        let radius = parts()
            .chain(corners())
            .map(|x| {
                (0..3)
                    .map(|i| (x[i] - center[i]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0_f64, f64::max);
        let parts = Bounds::of(parts());
        // Planar: no part leaves a plane normal to an axis of N and every
        // body turns about that axis only.
        let normal = (0..3).rev().find(|&k| {
            parts.high[k] - parts.low[k] <= STILL * size
                && poses.iter().all(|(_, pose)| {
                    pose.rotations
                        .iter()
                        .all(|r| (r[k][k] - 1.0).abs() <= STILL)
                })
        });
        Extent {
            center,
            size,
            radius: if radius > 0.0 { radius } else { size / 2.0 },
            normal,
        }
    }
}

/// An axis-aligned box around points.
struct Bounds {
    low: [f64; 3],
    high: [f64; 3],
}

impl Bounds {
    fn of(points: impl Iterator<Item = [f64; 3]>) -> Bounds {
        let mut bounds = Bounds {
            low: [f64::INFINITY; 3],
            high: [f64::NEG_INFINITY; 3],
        };
        for x in points {
            bounds.low = [0, 1, 2].map(|i| bounds.low[i].min(x[i]));
            bounds.high = [0, 1, 2].map(|i| bounds.high[i].max(x[i]));
        }
        bounds
    }

    /// The largest side, or 1 for an empty or single-point box.
    fn size(&self) -> f64 {
        let size = (0..3).fold(0.0_f64, |a, i| a.max(self.high[i] - self.low[i]));
        if size > 0.0 && size.is_finite() {
            size
        } else {
            1.0
        }
    }

    fn center(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| {
            let middle = (self.low[i] + self.high[i]) / 2.0;
            if middle.is_finite() { middle } else { 0.0 }
        })
    }
}

/// The indices of the samples at `times` to keep, at most `max` (at least
/// 2): all when there are few enough, else the first sample at or after
/// each of `max − 1` instants spaced evenly from the first time to the
/// last, and always the last sample.
pub fn decimate(times: &[f64], max: usize) -> Vec<usize> {
    let max = max.max(2);
    let n = times.len();
    if n <= max {
        return (0..n).collect();
    }
    let (start, end) = (times[0], times[n - 1]);
    let mut kept = Vec::with_capacity(max);
    let mut i = 0;
    for k in 0..max - 1 {
        let target = start + (end - start) * k as f64 / (max - 1) as f64;
        while i < n - 1 && times[i] < target {
            i += 1;
        }
        if kept.last() != Some(&i) {
            kept.push(i);
        }
    }
    if kept.last() != Some(&(n - 1)) {
        kept.push(n - 1);
    }
    kept
}

/// The unit quaternion `[w, x, y, z]` of a rotation matrix, `w ≥ 0`.
fn quaternion(r: &[[f64; 3]; 3]) -> [f64; 4] {
    let trace = r[0][0] + r[1][1] + r[2][2];
    let q = if trace > 0.0 {
        let s = 2.0 * (1.0 + trace).sqrt();
        [
            s / 4.0,
            (r[2][1] - r[1][2]) / s,
            (r[0][2] - r[2][0]) / s,
            (r[1][0] - r[0][1]) / s,
        ]
    } else if r[0][0] > r[1][1] && r[0][0] > r[2][2] {
        let s = 2.0 * (1.0 + r[0][0] - r[1][1] - r[2][2]).sqrt();
        [
            (r[2][1] - r[1][2]) / s,
            s / 4.0,
            (r[0][1] + r[1][0]) / s,
            (r[0][2] + r[2][0]) / s,
        ]
    } else if r[1][1] > r[2][2] {
        let s = 2.0 * (1.0 + r[1][1] - r[0][0] - r[2][2]).sqrt();
        [
            (r[0][2] - r[2][0]) / s,
            (r[0][1] + r[1][0]) / s,
            s / 4.0,
            (r[1][2] + r[2][1]) / s,
        ]
    } else {
        let s = 2.0 * (1.0 + r[2][2] - r[0][0] - r[1][1]).sqrt();
        [
            (r[1][0] - r[0][1]) / s,
            (r[0][2] + r[2][0]) / s,
            (r[1][2] + r[2][1]) / s,
            s / 4.0,
        ]
    };
    if q[0] < 0.0 { q.map(|x| -x) } else { q }
}

/// `x` with `decimals` decimals and no trailing zeros, as JSON.
fn rounded(x: f64, decimals: usize) -> String {
    if !x.is_finite() {
        return "null".into();
    }
    let text = format!("{x:.decimals$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        &text
    };
    match text {
        "-0" => "0".into(),
        other => other.into(),
    }
}

/// `x` to five significant digits, as JSON: plain between 1e-3 and 1e6,
/// else in exponent form.
fn rounded_significant(x: f64) -> String {
    let text = format!("{x:.4e}");
    let Ok(y) = text.parse::<f64>() else {
        return "null".into();
    };
    if !y.is_finite() {
        return "null".into();
    }
    if y == 0.0 || (1e-3..1e6).contains(&y.abs()) {
        return format!("{y}");
    }
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    format!(
        "{}e{exponent}",
        mantissa.trim_end_matches('0').trim_end_matches('.')
    )
}

/// A JSON string.
fn string(s: &str) -> String {
    serde_json::Value::from(s).to_string()
}

/// A JSON array of already-written values.
fn list(items: impl IntoIterator<Item = String>) -> String {
    let mut out = String::from("[");
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(&item);
    }
    out.push(']');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternion_of_a_turn_about_z() {
        let (s, c) = 0.3_f64.sin_cos();
        let q = quaternion(&[[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]);
        let expected = [0.15_f64.cos(), 0.0, 0.0, 0.15_f64.sin()];
        for i in 0..4 {
            assert!((q[i] - expected[i]).abs() < 1e-15, "{q:?}");
        }
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(rounded(1.230_04, 3), "1.23");
        assert_eq!(rounded(-0.000_01, 3), "0");
        assert_eq!(rounded(2.0, 3), "2");
        assert_eq!(rounded_significant(1.234_567e-7), "1.2346e-7");
        assert_eq!(rounded_significant(0.5), "0.5");
        assert_eq!(rounded_significant(-3e-9), "-3e-9");
        assert_eq!(rounded_significant(60.0), "60");
    }

    #[test]
    fn a_rod_along_x_from_its_inertia() {
        let (m, l) = (2.0, 0.6);
        let i = m * l * l / 12.0;
        let size = inertia_box((m, [[0.0, 0.0, 0.0], [0.0, i, 0.0], [0.0, 0.0, i]])).unwrap();
        assert!((size[0] - l).abs() < 1e-12 && size[1] == 0.0 && size[2] == 0.0);
        // A planar idealisation [0, 0, I] makes no box.
        assert_eq!(inertia_box((m, [[0.0; 3], [0.0; 3], [0.0, 0.0, i]])), None);
    }
}
