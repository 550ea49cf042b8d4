//! Several inputs where the loops have no closed form: a Stephenson six-bar whose second
//! ground pivot swings on a driven arm (`phi`, a second input) and whose crank's length is
//! a third (a driven slide, `r`). Newton on the coupled loops and every rate take all three,
//! the length input scaled with the mechanism.
use mechgen::mechanism;

mechanism! {
    pub struct Swinging {
        params: l1, l3, bc, cd, beta: angle, l4, l6, g;
        input: r: length, theta2: angle, phi: angle;
        unknowns: theta3: angle, theta4: angle, theta5: angle, theta6: angle;
        loop: r @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0;
        loop: l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi;
        point d = l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta);
    }
}

fn main() {
    let linkage = Swinging {
        l1: 5.0f64,
        l3: 5.5,
        bc: 3.0,
        cd: 4.5,
        beta: 0.5,
        l4: 4.0,
        l6: 5.0,
        g: 9.0,
    };
    let (r, theta2, phi) = (2.0, 1.0, 0.3);
    let guess = SwingingUnknowns {
        theta3: 0.3,
        theta4: 1.5,
        theta5: -0.5,
        theta6: 1.5,
    };
    let options = Default::default();
    let q = linkage.position(r, theta2, phi, &guess, &options).unwrap().value;
    let residual = linkage.residual(r, theta2, phi, &q);
    assert!(residual.iter().all(|f| f.abs() < 1e-12));
    let rates = (0.5, 2.0, -1.0);
    let v = linkage.velocity(r, theta2, phi, &q, rates.0, rates.1, rates.2).unwrap();
    // The rates by a central difference of Newton's positions along the inputs' motion.
    let h = 1e-6;
    let at = |t: f64| {
        let (r, theta2, phi) = (r + rates.0 * t, theta2 + rates.1 * t, phi + rates.2 * t);
        linkage.position(r, theta2, phi, &q, &options).unwrap().value.to_array()
    };
    let (before, after) = (at(-h), at(h));
    for ((b, a), rate) in before.iter().zip(after).zip(v.to_array()) {
        assert!(((a - b) / (2.0 * h) - rate).abs() < 1e-6, "{rate}");
    }
    let motion = linkage
        .motion_near(r, theta2, phi, &guess, &options, rates.0, rates.1, rates.2, 0.1, 0.2, 0.3)
        .unwrap()
        .value;
    let a = linkage
        .acceleration(r, theta2, phi, &q, rates.0, rates.1, rates.2, &v, 0.1, 0.2, 0.3)
        .unwrap();
    for (x, y) in motion.acceleration.to_array().iter().zip(a.to_array()) {
        assert!((x - y).abs() < 1e-9);
    }
    // The same mechanism a million times larger: the same angles.
    let large = Swinging {
        l1: 5e6,
        l3: 5.5e6,
        bc: 3e6,
        cd: 4.5e6,
        l4: 4e6,
        l6: 5e6,
        g: 9e6,
        ..linkage
    };
    let q_large = large.position(r * 1e6, theta2, phi, &guess, &options).unwrap().value;
    for (x, y) in q_large.to_array().iter().zip(q.to_array()) {
        assert!((x - y).abs() < 1e-12);
    }
    let d = linkage.points(r, theta2, phi, &q).unwrap().d;
    assert!(d.x.is_finite() && d.y.is_finite());
}
