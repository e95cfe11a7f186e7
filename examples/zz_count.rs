use rotorflow::algebra::{Multivector, Signature};
fn dense(sig: Signature) -> Multivector {
    let n = sig.dim();
    let mut b = Multivector::zero(sig);
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            let c = 0.1 + 0.5 * ((k as f64) * 1.7 + 0.3).sin().abs();
            b.as_mut_slice()[(1usize << i) | (1usize << j)] = if k % 3 == 1 { -c } else { c };
            k += 1;
        }
    }
    b
}
fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let sig = Signature::new(args[0], args[1], args[2]).unwrap();
    let b = dense(sig);
    let mut acc = 0.0;
    for _ in 0..args[3] {
        acc += std::hint::black_box(&b).exp().unwrap().as_slice()[0];
    }
    println!("{acc}");
}
