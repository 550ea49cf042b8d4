//! mechgen's `nalgebra` feature: the generated unknowns and Jacobians as nalgebra vectors
//! and matrices, the right way round (row `i` of the matrix is loop equation `i`, column `j`
//! unknown `j`), and `Vec2` with nalgebra's vectors and points.

use mechanisms::{FourBar, WattSixBar, WattSixBarUnknowns};
use mechgen::nalgebra_support::{matrix, unknowns, vector};
use mechgen::{Branch, Vec2};
use nalgebra::{Matrix2, Matrix4, Point2, SMatrix, Vector2, Vector4};

fn watt() -> WattSixBar<f64> {
    WattSixBar::new(
        [180.0, 80.0, 200.0, 150.0],
        100.0,
        0.8,
        220.0,
        160.0,
        (300.0, 150.0),
    )
    .unwrap()
}

#[test]
fn the_jacobian_matrix_has_loop_equations_as_rows_and_unknowns_as_columns() {
    let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let theta2 = 60f64.to_radians();
    let q = linkage.assemble(theta2, Branch::Open).unwrap();
    let (l3, l4) = (200.0, 150.0);
    // The loop l2·e^{iθ2} + l3·e^{iθ3} − l4·e^{iθ4} − l1: its x equation (row 0) and its y
    // equation (row 1), differentiated by θ3 (column 0) and θ4 (column 1).
    let by_hand = Matrix2::new(
        -l3 * q.theta3.sin(),
        l4 * q.theta4.sin(),
        l3 * q.theta3.cos(),
        -l4 * q.theta4.cos(),
    );
    let jacobian = linkage.jacobian(theta2, &q);
    assert!((matrix(jacobian) - by_hand).abs().max() < 1e-12);
    // nalgebra's own conversion reads the rows as columns: the transpose.
    assert_eq!(SMatrix::from(jacobian), matrix(jacobian).transpose());
}

#[test]
fn the_jacobian_matrix_of_a_two_loop_mechanism_is_the_residual_s_derivative() {
    let linkage = watt();
    let theta2 = 1.0;
    let q = linkage
        .assemble(theta2, [Branch::Open, Branch::Open])
        .unwrap();
    let j: Matrix4<f64> = matrix(linkage.jacobian(theta2, &q));
    let h = 1e-6;
    for column in 0..4 {
        let shifted = |by: f64| {
            let mut values = vector(q);
            values[column] += by;
            let residual =
                linkage.residual(theta2, &unknowns::<_, WattSixBarUnknowns<f64>, 4>(values));
            Vector4::from(residual)
        };
        let derivative = (shifted(h) - shifted(-h)) / (2.0 * h);
        assert!(
            (j.column(column) - derivative).abs().max() < 1e-6 * 300.0,
            "column {column}: {} against {derivative}",
            j.column(column)
        );
    }
}

#[test]
fn nalgebra_s_solve_of_the_jacobian_gives_the_generated_velocity() {
    let linkage = watt();
    let theta2 = 1.0;
    let q = linkage
        .assemble(theta2, [Branch::Open, Branch::Crossed])
        .unwrap();
    let rate = 10.0;
    let j = matrix(linkage.jacobian(theta2, &q));
    let rhs = -Vector4::from(linkage.input_jacobian(theta2, &q)) * rate;
    let solved = j.lu().solve(&rhs).unwrap();
    let generated = vector(linkage.velocity(theta2, &q, rate).unwrap());
    assert!((solved - generated).abs().max() < 1e-9 * generated.abs().max());
}

#[test]
fn unknowns_go_to_a_vector_and_back_in_declaration_order() {
    let q = WattSixBarUnknowns {
        theta3: 0.1,
        theta4: 0.2,
        theta5: 0.3,
        theta6: 0.4,
    };
    let v = vector(q);
    assert_eq!(v, Vector4::new(0.1, 0.2, 0.3, 0.4));
    assert_eq!(unknowns::<_, WattSixBarUnknowns<f64>, 4>(v), q);
    // The same by hand, through the arrays nalgebra converts.
    assert_eq!(WattSixBarUnknowns::from_array(v.into()), q);
    assert_eq!(Vector4::from(q.to_array()), v);
}

#[test]
fn vec2_converts_with_vector2_and_point2_both_ways() {
    let v = Vec2::new(1.5_f32, -2.0);
    assert_eq!(Vector2::from(v), Vector2::new(1.5, -2.0));
    assert_eq!(Point2::from(v), Point2::new(1.5, -2.0));
    assert_eq!(Vec2::from(Vector2::new(1.5, -2.0)), v);
    assert_eq!(Vec2::from(Point2::new(1.5, -2.0)), v);
}
