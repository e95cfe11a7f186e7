//! JSON input of the algebra types (feature `serde`): `serde_json` deserialisation of
//! `Signature`, `Vector`, `Bivector`, `Rotor` and `Multivector` from arbitrary bytes.
//!
//! Asserts: no panic; an accepted value has finite components, serialises back to JSON that
//! deserialises to the same value, and its basic operations (norms, products with itself,
//! exp/log, rotation, inverse, dual) neither panic nor, where the result is finite by
//! contract, give NaN.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::algebra::{Bivector, Multivector, Rotor, Signature, Vector};

fn round_trip<T>(value: &T)
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + std::fmt::Debug,
{
    let text = serde_json::to_string(value).expect("an accepted value serialises");
    let back: T = serde_json::from_str(&text).expect("its JSON deserialises");
    assert_eq!(&back, value, "JSON {text}");
}

fn finite(xs: &[f64]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

fuzz_target!(|data: &[u8]| {
    if let Ok(s) = serde_json::from_slice::<Signature>(data) {
        round_trip(&s);
    }
    if let Ok(v) = serde_json::from_slice::<Vector>(data) {
        round_trip(&v);
        assert!(finite(v.as_slice()));
        let _ = v.norm();
        let _ = v.try_normalize();
        let w = v.wedge(&v);
        assert!(
            w.as_slice().iter().all(|x| !x.is_nan()),
            "{v:?} ∧ itself = {w:?}"
        );
    }
    if let Ok(b) = serde_json::from_slice::<Bivector>(data) {
        round_trip(&b);
        assert!(finite(b.as_slice()));
        let _ = b.norm();
        let _ = b.commutator(&b);
        if b.dim() <= 16 {
            let r = b.exp();
            assert!(finite(r.as_slice()), "exp {b:?} = {r:?}");
        }
    }
    if let Ok(r) = serde_json::from_slice::<Rotor>(data) {
        round_trip(&r);
        assert!(finite(r.as_slice()));
        let _ = r.unit_error();
        let _ = r.reverse();
        let _ = r.compose(&r);
        let m = r.to_matrix();
        assert!(m.iter().all(|x| !x.is_nan()), "matrix of {r:?}: {m}");
        let log = r.log();
        assert!(finite(log.as_slice()), "log {r:?} = {log:?}");
        if r.dim() >= 1 {
            let x = r.rotate_vector(&Vector::basis(r.dim(), 0));
            assert!(
                x.as_slice().iter().all(|c| !c.is_nan()),
                "{r:?} rotates e1 to {x:?}"
            );
        }
    }
    if let Ok(m) = serde_json::from_slice::<Multivector>(data) {
        round_trip(&m);
        assert!(finite(m.as_slice()));
        let _ = m.norm();
        let _ = m.reverse();
        let _ = m.geometric(&m);
        let _ = m.wedge(&m);
        let _ = m.inverse();
        let _ = m.dual();
        let _ = m.grades();
    }
});
