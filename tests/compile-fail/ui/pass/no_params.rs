//! A declaration without `params` (its magnitudes the input and the unknowns): its struct
//! has no field to give, so `new()` (or `Default`) builds it, and every generated function
//! compiles and solves, the closed form and a scene included.
use mechgen::mechanism;

mechanism! {
    /// A slider at 45° pushed along x by `d`: `x` up, `y` along the slider.
    pub struct Slide {
        input: d: length;
        unknowns: x: length, y: length;
        loop: d @ 0 + x @ (pi / 2) - y @ (pi / 4);
        point tip = d @ 0 + x @ (pi / 2);
        scene state: x, tip_dot;
        generate: position, velocity, acceleration, sensitivities;
    }
}

fn main() {
    let slide = Slide::new();
    assert_eq!(slide, Slide::default());
    let guess = SlideUnknowns { x: 0.0, y: 0.0 };
    let q = slide.position(2.0f64, &guess, &Default::default()).unwrap().value;
    assert!((q.x - 2.0).abs() < 1e-12 && (q.y - 2f64.sqrt() * 2.0).abs() < 1e-12);
    let v = slide.velocity(2.0, &q, 3.0).unwrap();
    assert!((v.x - 3.0).abs() < 1e-12);
    let a = slide.acceleration(2.0, &q, 3.0, &v, 0.0).unwrap();
    assert!(a.x.abs() < 1e-12);
    let tip = slide.points(2.0, &q).unwrap().tip;
    assert!((tip.x - 2.0).abs() < 1e-12 && (tip.y - 2.0).abs() < 1e-12);
    let assembled = slide.assemble(2.0).unwrap();
    assert!((assembled.x - q.x).abs() < 1e-12 && (assembled.y - q.y).abs() < 1e-12);
    let state = slide.scenes().unwrap().state(2.0, 3.0).unwrap();
    assert!((state.x - 2.0).abs() < 1e-12 && (state.tip_dot.y - 3.0).abs() < 1e-12);
    // Nothing to design, but the `Design` impl still says so in its arrays.
    use mechgen::Design;
    assert_eq!(slide.parameters(), [0.0f64; 0]);
    assert_eq!(Slide::<f64>::with_parameters([]), slide);
    let none: [[f64; 2]; 0] = Design::unknown_sensitivities(&slide, 2.0, q.to_array()).unwrap();
    assert!(none.is_empty());
    let tip = Design::point_positions(&slide, 2.0, q.to_array()).unwrap();
    assert!((tip[0].x - 2.0).abs() < 1e-12);
}
