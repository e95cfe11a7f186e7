//! Processed compositions of the Lie–Poisson splitting (Blanes, Casas and Murua): a cheap
//! kernel of Strang steps whose error the processor, applied once before and once after a
//! run, turns into that of a method of higher order.

use super::DynamicsError;
use super::splitting::strang_drift;
use crate::dynamics::RigidBody;

/// Which processed method [`ProcessedSplitting`] runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProcessedOrder {
    /// Effective order 6: a kernel of seven Strang steps, a processor of ten (Blanes, Casas
    /// and Ros, *Processed symplectic integrators for Hamiltonian systems*, 2001; the method
    /// BLA01 of Blanes, Casas and Murua, *Splitting methods for differential equations*,
    /// Acta Numerica 2024, table 8.1).
    Six,
    /// Effective order 8: a kernel of thirteen Strang steps, a processor of twenty (BCM06
    /// in the same table).
    Eight,
}

/// BLA01: the kernel's weights a₁, a₂, a₃ (a₄ = 1 − 2(a₁ + a₂ + a₃), then mirrored) and the
/// processor's γ₂ … γ₅ (γ₁ = −(γ₂ + … + γ₅), then γ₁₁₋ₖ = −γₖ).
const SIX_KERNEL: [f64; 3] = [0.513910778424374, 0.364193022833858, -0.867423280969274];
const SIX_PROCESSOR: [f64; 4] = [
    -0.461165940466494,
    -0.074332422810238,
    0.384998538774070,
    0.375012038697862,
];

/// BCM06 of order 8: the kernel's a₁ (twice), a₃ … a₆ (the middle weight makes the sum 1)
/// and the processor's γ₂ … γ₁₀ (γ₁ from the zero sum, then γ₂₁₋ₖ = −γₖ).
const EIGHT_KERNEL: [f64; 6] = [
    0.168,
    0.168,
    0.585550530805562,
    -0.460090457516872,
    0.172863148729731,
    0.179664539695039,
];
const EIGHT_PROCESSOR: [f64; 9] = [
    -0.008488123494574411,
    -0.337188967354338,
    0.333987768164597,
    0.588351189003849,
    0.162324207599241,
    -0.511744926116413,
    0.236885952363384,
    0.598212975943381,
    -0.543415765371656,
];

/// A processed composition of the Lie–Poisson splitting of the free body (Blanes, Casas and
/// Murua): ψ = π ∘ κ ∘ π⁻¹, with the kernel κ a symmetric composition of Strang steps and
/// the processor π a composition of Strang steps whose weights sum to zero. Over n steps
/// ψⁿ = π ∘ κⁿ ∘ π⁻¹, so the processor is paid once per run and each step costs the
/// kernel's steps alone: seven Strang steps for effective order 6 (against nine for
/// [`Splitting::kahan_li6`](super::Splitting::kahan_li6)), thirteen for order 8 (against
/// seventeen).
///
/// Every substep is an exact rotation of L and of the attitude, so the Casimirs and the
/// space-frame momentum stay at round-off, as for [`Splitting`](super::Splitting). The
/// processing needs an autonomous problem: free bodies (no torque), whose inertia is diagonal
/// on the basis planes. The state between the processor's two applications is not the
/// body's state; [`ProcessedSplitting::advance`] therefore runs whole stretches, not single
/// steps of an [`Integrator`](super::Integrator).
///
/// ```
/// use rotorflow::dynamics::{Invariants, ProcessedOrder, ProcessedSplitting};
/// use rotorflow::prelude::*;
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0])?;
/// let l = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?;
/// let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(4), &l)?;
/// let start = Invariants::of(&body);
/// // To t = 10 in 100 steps, effective order 8.
/// ProcessedSplitting::new(ProcessedOrder::Eight).advance(&mut body, 0.1, 100)?;
/// assert!(Invariants::of(&body).drift_from(&start).casimirs < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct ProcessedSplitting {
    order: ProcessedOrder,
}

impl ProcessedSplitting {
    /// The processed method of the given effective order.
    pub fn new(order: ProcessedOrder) -> Self {
        ProcessedSplitting { order }
    }

    /// The effective order: 6 or 8.
    pub fn order(&self) -> u32 {
        match self.order {
            ProcessedOrder::Six => 6,
            ProcessedOrder::Eight => 8,
        }
    }

    /// Strang steps per step (the kernel's; the processor adds a fixed number per run).
    pub fn stages(&self) -> usize {
        self.kernel().len()
    }

    /// The kernel's weights (symmetric, summing to 1).
    pub fn kernel(&self) -> Vec<f64> {
        let half: &[f64] = match self.order {
            ProcessedOrder::Six => &SIX_KERNEL,
            ProcessedOrder::Eight => &EIGHT_KERNEL,
        };
        let middle = 1.0 - 2.0 * half.iter().sum::<f64>();
        half.iter()
            .copied()
            .chain([middle])
            .chain(half.iter().rev().copied())
            .collect()
    }

    /// The processor's weights γ₁, …, γᵣ (antisymmetric, summing to 0): π applies the
    /// Strang steps of γᵣh first and of γ₁h last.
    pub fn processor(&self) -> Vec<f64> {
        let rest: &[f64] = match self.order {
            ProcessedOrder::Six => &SIX_PROCESSOR,
            ProcessedOrder::Eight => &EIGHT_PROCESSOR,
        };
        let first = -rest.iter().sum::<f64>();
        let half: Vec<f64> = [first].into_iter().chain(rest.iter().copied()).collect();
        half.iter()
            .copied()
            .chain(half.iter().map(|g| -g))
            .collect()
    }

    /// Advances a free body by `steps` steps of size `h`: the processor's inverse, the
    /// kernel `steps` times, the processor.
    ///
    /// # Errors
    /// [`DynamicsError::UnsupportedInertia`] unless the inertia map is diagonal on the basis
    /// planes; [`DynamicsError::InvalidSampling`] for a step that is not finite;
    /// [`DynamicsError::NonFinite`] if the state stops being finite (the body is then left as
    /// it was).
    pub fn advance(&self, body: &mut RigidBody, h: f64, steps: usize) -> Result<(), DynamicsError> {
        let name = match self.order {
            ProcessedOrder::Six => "processed-splitting6",
            ProcessedOrder::Eight => "processed-splitting8",
        };
        body.refuse_gyrostat(name)?;
        let Some(moments) = body.inertia().diagonal_plane_moments() else {
            return Err(DynamicsError::UnsupportedInertia { integrator: name });
        };
        if !h.is_finite() {
            return Err(DynamicsError::InvalidSampling {
                reason: "the step must be finite",
            });
        }
        let moments: smallvec::SmallVec<[f64; 28]> = moments.iter().copied().collect();
        let (kernel, processor) = (self.kernel(), self.processor());
        let saved = (
            body.principal_frame_attitude().clone(),
            body.momentum().clone(),
        );
        // π⁻¹: the processor's steps backwards, each negated (a Strang step of −τ undoes
        // one of τ).
        for &g in &processor {
            strang_drift(body, &moments, -g * h);
        }
        for _ in 0..steps {
            for &g in &kernel {
                strang_drift(body, &moments, g * h);
            }
        }
        for &g in processor.iter().rev() {
            strang_drift(body, &moments, g * h);
        }
        if !body.momentum().as_slice().iter().all(|x| x.is_finite())
            || !body.principal_frame_attitude().is_finite()
        {
            body.set_state(saved.0, saved.1)?;
            return Err(DynamicsError::NonFinite {
                time: h * steps as f64,
            });
        }
        Ok(())
    }
}
