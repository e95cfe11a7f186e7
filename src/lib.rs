//! # rotorflow
//!
//! Geometric algebra for rigid bodies in any number of dimensions: the algebra, the
//! inertia, the rotation and the motion, with contact.
//!
//! rotorflow says the physics of rigid bodies in ℝᴺ with the objects geometric algebra gives
//! it: angular velocity and momentum are bivectors, attitude is a rotor, inertia is a linear
//! map on bivectors, and a placement is a motor of projective GA. The dimension is chosen at
//! run time; the algebra itself is there in every signature.
//!
//! The layers, each building on the one before:
//! - [`algebra`]: vectors, bivectors, rotors and multivectors of any signature Cl(p, q, r),
//!   every product, and closed-form exponentials and logarithms that stay exact where other
//!   libraries fail (non-simple and isoclinic bivectors, angles near π, N above 4); typed
//!   objects of projective GA ([`algebra::pga`]: points, lines, planes, motors), conformal GA
//!   ([`algebra::cga`]) and the spacetime algebra ([`algebra::sta`]); and the fixed-size 3D
//!   and 4D types [`Rotor3`](algebra::Rotor3), [`Rotor4`](algebra::Rotor4),
//!   [`Bivector3`](algebra::Bivector3), [`Bivector4`](algebra::Bivector4) in f32 and f64
//!   (`Copy`, on the stack; glam conversions with the feature `glam`);
//! - [`inertia`]: the inertia map as a linear operator on bivectors, built from a catalogue
//!   of N-dimensional bodies (point clouds, the paper's tesseract and 5-cell, cuboids,
//!   ellipsoids, balls, shells, simplices, simplicial meshes, composites), with the paper's
//!   rank-4 and Levi-Civita-contracted tensors as views;
//! - [`dynamics`]: rigid bodies turning, with eight integrators, drift monitors and the free
//!   top as the integrable system it is (closed forms, Jacobi elliptic functions in 3D, and
//!   the discrete Moser–Veselov top that keeps every Manakov integral); and bodies that move
//!   ([`dynamics::motion`]): systems with forces, springs and joints, contact with half-spaces
//!   and between bodies (contact manifolds held at the corners of each contact region, so
//!   that towers of boxes and 4D hypercubes stand), and recorded runs;
//! - `viz` and `scene` (features of the same names): pictures of what `dynamics` records,
//!   and scene files, used by the `rotorflow` command and open to any program
//!   (algebra ← inertia ← dynamics ← viz ← scene ← cli);
//! - [`special`]: Carlson's symmetric elliptic integrals, the Legendre integrals of the
//!   first, second and third kinds, and the Jacobi elliptic functions, accurate to a few ulp
//!   (the building blocks of the exact free 3D rigid body).
//!
//! The same crate is a Python package (`pip install ./python` from the repository, PyO3 and
//! numpy; the book's chapter "From Python").
//!
//! # Conventions
//! The Conventions chapter of the rotorflow book states them in full; in short:
//! - Bivector components are ordered 12, 13, …, 1N, 23, …; API indices are 0-based and
//!   every printed name is 1-based (`Bivector::get(0, 1)` is the e₁₂ component). The skew
//!   matrix \[B\] has \[B\]ᵢⱼ = Bᵢⱼ.
//! - Signatures Cl(p, q, r) put the p positive, then the q negative, then the r null basis
//!   vectors; a basis blade is indexed by a bit mask, bit i − 1 for eᵢ.
//! - Angular velocity ω is a body-frame bivector; body point x moves with x⌋ω = \[ω\]ᵀx, so
//!   ω = θ̇ e₁∧e₂ turns e₁ toward e₂. In 3D the axial vector is Ω = (ω₂₃, −ω₁₃, ω₁₂).
//! - The attitude R maps body to space, x ↦ R x R̃; R = exp(−θB̂/2) turns by θ in the plane B̂,
//!   dR/dt = −½Rω, and the rotation matrix of R is expm(\[θB̂\]ᵀ).
//! - The mass tensor J = Σ m x xᵀ has the **second moments** Jᵢ as eigenvalues. The inertia
//!   map is I(ω) = Σ m x∧(x⌋ω), \[I(ω)\] = J\[ω\] + \[ω\]J; in the principal frame it
//!   multiplies the plane eᵢ∧eⱼ by its **plane moment** Jᵢ + Jⱼ. In 3D the plane moments are
//!   the classical **moments of inertia** I₁ = J₂ + J₃, I₂ = J₁ + J₃, I₃ = J₁ + J₂. Any
//!   symmetric positive-definite map on bivectors is accepted as well.
//! - L = I(ω), T = ½⟨ω, L⟩, and Euler's equations read dL/dt = ω × L + τ with the commutator
//!   product A × B = ½(AB − BA). Free motion keeps the space-frame L, T and the Casimirs of L.
//! - The paper's rank-4 tensor is its eq. (22) read literally, Iⁱʲⁱʲ = ½(Jᵢ + Jⱼ), with
//!   Lᵢⱼ = Σₖₗ Iⁱʲᵏˡ ωₖₗ summed over all k and l.
//!
//! The paper is *Tensor Formalism for Rotating Bodies in Multidimensional Euclidian Space*,
//! preprint, 4 August 2025, doi:10.20944/preprints202508.0136.v1; the sources the crate
//! builds on are listed in the References chapter of the book.
//!
//! # Quick start
//! ```
//! use rotorflow::prelude::*;
//!
//! // The double rotation of 4D: 0.5 rad in the e1e2 plane and 1.2 rad in the e3e4 plane.
//! let theta = Bivector::from_components(4, &[0.5, 0.0, 0.0, 0.0, 0.0, 1.2])?;
//! let r = Rotor::from_rotation_bivector(&theta);
//!
//! // Its matrix is the exponential of the skew matrix (transposed): see the conventions.
//! let q = r.to_matrix();
//! assert!((q[(1, 0)] - 0.5f64.sin()).abs() < 1e-15);
//!
//! // The invariant decomposition recovers the two planes.
//! let planes = theta.decompose();
//! assert_eq!(planes.len(), 2);
//! assert!((planes.magnitudes()[0] - 1.2).abs() < 1e-15);
//!
//! // And the logarithm gives the bivector back.
//! assert!((&r.rotation_bivector() - &theta).norm() < 1e-14);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```
//!
//! The inertia of a 4D body, as a map from angular velocity to angular momentum:
//! ```
//! use rotorflow::prelude::*;
//! let body = Body::solid_ellipsoid(&[1.0, 2.0, 3.0, 4.0], 1.0)?;
//! let inertia = InertiaMap::from_body(&body)?;
//! let omega = Bivector::from_plane(4, 0, 1, 1.0)?;  // spin in the e1e2 plane
//! let l = inertia.apply(&omega);                    // L = I(ω) = (J₁ + J₂) e₁₂ here
//! let j = body.mass_tensor();
//! assert!((l.get(0, 1) - (j[(0, 0)] + j[(1, 1)])).abs() < 1e-12);
//! assert!((&inertia.apply_inverse(&l) - &omega).norm() < 1e-14);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The book
//! The rotorflow book (`book/` in the repository; `scripts/book.sh` builds it with these API
//! docs beside it) explains the crate chapter by chapter: getting started, the conventions,
//! geometric algebra in N dimensions ([`algebra`]) and in other signatures (motors, boosts,
//! versors), the mapping of every equation of the paper onto the crate, the inertia of
//! N-dimensional bodies ([`inertia`]), the integrators and what each conserves
//! ([`dynamics`]), closed-form motion, bodies that move and touch
//! ([`dynamics::motion`]), the paper's errata with the test behind each one, extending the
//! crate, performance beside nalgebra and glam, the Python package, the command-line
//! reference, scene files and the references.
//!
//! # Crate features
//! - `cli` (default): the `rotorflow` command (`cargo run --release -- demo`), a user of
//!   `viz` and `scene`, which it turns on. Turning it off (`default-features = false`)
//!   drops clap, plotters, serde_json, toml, indicatif, rayon and tempfile (and `viz` and
//!   `scene` unless asked for); the rest of the library is the same.
//! - `viz`: `rotorflow::viz`, the pictures (plotters, serde_json): HTML animations of a
//!   turning body or of a recorded run of moving bodies
//!   ([`SystemTrajectory`](crate::dynamics::motion::SystemTrajectory)), contacts marked,
//!   SVG plots and projections.
//! - `scene`: `rotorflow::scene`, scene files (serde, toml): read, run and written as JSON
//!   and CSV as `rotorflow scene` does, with its one-line errors.
//! - `serde`: `Serialize`/`Deserialize` for every algebra type (deserialisation validates
//!   lengths, finiteness, and that a rotor is on Spin(N)) and for recorded runs, with their
//!   JSON text. Off by default.
//!
//! # Performance
//! Vectors and bivectors up to N = 8 and rotors up to N = 5 live on the stack. The bivector
//! commutator costs O(N³) without forming a multivector; exp and log are closed forms. The
//! benches in `benches/algebra.rs` compare each kernel with nalgebra's matrix formulation,
//! those in `benches/fixed.rs` the fixed-size types with glam and nalgebra.
//!
//! # When not to use rotorflow
//! For 3D graphics alone, glam or nalgebra's quaternions are smaller dependencies; rotorflow's
//! fixed-size [`Rotor3`](algebra::Rotor3) is their equal in f32 and f64 (compare them with
//! `cargo bench --bench fixed`), but the crate around it is built for any dimension and any
//! signature.
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod algebra;
/// The nalgebra crate rotorflow is built on (its matrices and the vectors of the fixed-size
/// rotors), re-exported so that no second nalgebra dependency of a matching version is
/// needed.
pub use nalgebra;
pub mod dynamics;
pub mod inertia;
mod numeric;
#[cfg(feature = "scene")]
pub mod scene;
pub mod special;
#[cfg(feature = "viz")]
pub mod viz;

/// The types most programs need: `use rotorflow::prelude::*;`.
///
/// The algebra (vectors, bivectors, rotors, multivectors), the inertia (bodies and their
/// inertia maps) and the dynamics: [`RigidBody`](crate::dynamics::RigidBody), its
/// [`Attitude`](crate::dynamics::Attitude), the integrators behind the
/// [`Integrator`](crate::dynamics::Integrator) trait ([`Rkmk4`](crate::dynamics::Rkmk4),
/// [`Splitting`](crate::dynamics::Splitting) (Strang and Yoshida),
/// [`Midpoint`](crate::dynamics::Midpoint), [`MoserVeselov`](crate::dynamics::MoserVeselov),
/// [`Dopri5`](crate::dynamics::Dopri5), [`Dop853`](crate::dynamics::Dop853)),
/// [`simulate`](crate::dynamics::simulate) and its [`Trajectory`](crate::dynamics::Trajectory),
/// the torques ([`Torque`](crate::dynamics::Torque), [`Free`](crate::dynamics::torques::Free)
/// for free rotation, the module [`torques`](crate::dynamics::torques) for the others), and
/// each layer's error type.
///
/// A free 3D body integrated and checked against its closed-form motion:
/// ```
/// use rotorflow::prelude::*;
///
/// // In 3D the plane moments (I₁₂, I₁₃, I₂₃) are the classical moments of inertia about the
/// // axes e₃, e₂, e₁. The body spins mostly in the e₁₃ plane, about its middle axis.
/// let inertia = InertiaMap::from_plane_moments(&[3.0, 4.0, 5.0])?;
/// let omega = Bivector::from_components(3, &[0.2, 1.0, 0.1])?;
/// let body = RigidBody::from_body_velocity(inertia, Rotor::identity(3), &omega)?;
///
/// // Ten time units with the fourth-order splitting, steps of at most 0.01, one sample per unit.
/// let times: Vec<f64> = (0..=10).map(f64::from).collect();
/// let trajectory = simulate(&body, &mut Splitting::yoshida4(), &Free, 0.01, &times)?;
///
/// // A splitting keeps the space-frame momentum to round-off …
/// assert!(trajectory.drift().space_momentum < 1e-12);
/// // … and follows the closed-form motion of the free top.
/// let exact = body.exact_solution()?;
/// let last = trajectory.samples().last().expect("eleven samples");
/// let l_exact = exact.momentum_at(10.0)?;
/// assert!((&last.momentum - &l_exact).norm() < 1e-6 * l_exact.norm());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub mod prelude {
    pub use crate::algebra::{
        AlgebraError, Bivector, Decomposition, Multivector, Product, Rotor, Signature, Vector,
    };
    pub use crate::dynamics::torques::{self, Free};
    pub use crate::dynamics::{
        Attitude, Dop853, Dopri5, DynamicsError, Integrator, LiePoissonRk4, Midpoint, MoserVeselov,
        RigidBody, Rkmk4, Splitting, SplittingOrder, Torque, Trajectory, simulate,
    };
    pub use crate::inertia::{Body, InertiaError, InertiaMap};
}

/// The README's code blocks, compiled and run as doctests so that the README stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
