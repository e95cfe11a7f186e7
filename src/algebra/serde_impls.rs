//! `serde` support (feature `serde`). Every type serialises as its dimension (or signature)
//! and its components in the documented order; deserialisation validates the lengths and
//! finiteness through the checked constructors, so malformed data is an error, not a value.
//!
//! Serialisation writes each component's shortest round-trip decimal. To read it back bit
//! for bit with `serde_json`, enable that crate's `float_roundtrip` feature (rotorflow's own
//! `cli` feature does): its default float parser can be one ulp off for long literals.

use super::{AlgebraError, Bivector, Multivector, Rotor, Signature, Vector};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Serialize, Deserialize)]
struct SignatureRepr {
    p: usize,
    q: usize,
    r: usize,
}

impl Serialize for Signature {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        SignatureRepr {
            p: self.p(),
            q: self.q(),
            r: self.r(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Signature {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = SignatureRepr::deserialize(d)?;
        Signature::new(r.p, r.q, r.r).map_err(serde::de::Error::custom)
    }
}

#[derive(Serialize, Deserialize)]
struct GradedRepr {
    dim: usize,
    components: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
struct MultivectorRepr {
    signature: Signature,
    coefficients: Vec<f64>,
}

fn de_err<E: serde::de::Error>(e: AlgebraError) -> E {
    E::custom(e)
}

impl Serialize for Vector {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        GradedRepr {
            dim: self.dim(),
            components: self.as_slice().to_vec(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Vector {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = GradedRepr::deserialize(d)?;
        if r.components.len() != r.dim {
            return Err(de_err(AlgebraError::WrongComponentCount {
                what: "vector",
                expected: r.dim,
                found: r.components.len(),
            }));
        }
        Vector::from_components(&r.components).map_err(de_err)
    }
}

impl Serialize for Bivector {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        GradedRepr {
            dim: self.dim(),
            components: self.as_slice().to_vec(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Bivector {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = GradedRepr::deserialize(d)?;
        Bivector::from_components(r.dim, &r.components).map_err(de_err)
    }
}

impl Serialize for Rotor {
    /// As the dimension and the 2^N multivector coefficients indexed by blade mask (the
    /// portable layout), odd ones zero.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        GradedRepr {
            dim: self.dim(),
            components: self.to_multivector().as_slice().to_vec(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Rotor {
    /// Checks that the data is a rotor ([`Rotor::from_multivector`]).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = GradedRepr::deserialize(d)?;
        let sig = Signature::new(r.dim, 0, 0).map_err(de_err)?;
        let m = Multivector::from_coefficients(sig, &r.components).map_err(de_err)?;
        Rotor::from_multivector(&m).map_err(de_err)
    }
}

impl Serialize for Multivector {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        MultivectorRepr {
            signature: self.signature(),
            coefficients: self.as_slice().to_vec(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Multivector {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = MultivectorRepr::deserialize(d)?;
        Multivector::from_coefficients(r.signature, &r.coefficients).map_err(de_err)
    }
}
