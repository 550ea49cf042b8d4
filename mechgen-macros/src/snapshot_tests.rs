//! Snapshots of the expansion of every mechanism we ship, formatted by prettyplease.
//!
//! The declarations are read from the `mechanisms` crate's source, so the snapshots always
//! show the code users of those mechanisms compile. Snapshots live in
//! `tests/snapshots/expansion/` with the workspace's other snapshots.

use quote::ToTokens;

fn shipped_declarations() -> Vec<(String, proc_macro2::TokenStream)> {
    let directory = concat!(env!("CARGO_MANIFEST_DIR"), "/../mechanisms/src");
    let mut paths: Vec<_> = std::fs::read_dir(directory)
        .expect("mechanisms/src is readable")
        .map(|entry| entry.expect("directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "rs"))
        .collect();
    paths.sort();
    declarations_in(&paths)
}

/// Every `mechanism!` invocation in `paths`, by name.
fn declarations_in(paths: &[std::path::PathBuf]) -> Vec<(String, proc_macro2::TokenStream)> {
    paths
        .iter()
        .flat_map(|path| {
            let source = std::fs::read_to_string(path).expect("source is readable");
            syn::parse_file(&source).expect("source parses").items
        })
        .filter_map(|item| match item {
            syn::Item::Macro(item) if item.mac.path.is_ident("mechanism") => {
                let tokens = item.mac.tokens;
                let declaration: crate::ast::Declaration =
                    syn::parse2(tokens.clone()).expect("shipped declaration parses");
                Some((declaration.name.to_string(), tokens))
            }
            _ => None,
        })
        .collect()
}

fn pretty(tokens: proc_macro2::TokenStream) -> String {
    let file: syn::File = syn::parse2(tokens).expect("expansion is valid Rust");
    prettyplease::unparse(&file)
}

fn assert_expansion(name: &str, expansion: &str) {
    insta::with_settings!({
        snapshot_path => "../../tests/snapshots/expansion",
        prepend_module_to_snapshot => false,
        omit_expression => true,
    }, {
        insta::assert_snapshot!(name, expansion);
    });
}

#[test]
fn shipped_mechanism_expansions() {
    let declarations = shipped_declarations();
    let names: Vec<&str> = declarations.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "FiveBar",
            "FourBar",
            "InvertedSliderCrank",
            "JansenLeg",
            "WattSixBar",
            "StephensonSixBar",
            "SliderCrank"
        ]
    );
    for (name, tokens) in declarations {
        let expansion = pretty(crate::expand::expand(tokens.into_token_stream()));
        assert_expansion(&name, &expansion);
    }
}

/// The performance report's scenes (the four-bar asking for less and less), whose expansion
/// sizes it quotes.
#[test]
fn scene_expansions() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/src/scenes.rs");
    let declarations = declarations_in(&[path.into()]);
    assert_eq!(declarations.len(), 3);
    for (name, tokens) in declarations {
        assert_expansion(&name, &pretty(crate::expand::expand(tokens)));
    }
}

/// A declaration that asks for positions only gets no velocity, acceleration or input
/// Jacobian code.
#[test]
fn position_only_expansion() {
    let declaration = quote::quote! {
        /// Four-bar, positions only.
        pub struct FourBarPositions {
            params: l1, l2, l3, l4;
            input: theta2: angle;
            unknowns: theta3: angle, theta4: angle;
            loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
            point coupler_pin = l2 @ theta2 + l3 @ theta3;
            generate: position;
        }
    };
    let expansion = pretty(crate::expand::expand(declaration));
    for absent in [
        "fn velocity",
        "fn acceleration",
        "fn input_jacobian",
        "fn point_velocities",
    ] {
        assert!(!expansion.contains(absent), "{absent} was generated");
    }
    assert_expansion("FourBarPositions", &expansion);
}

/// The columns a Newton position's error moves (`mechgen::Accuracy::estimate_at`'s `moving`),
/// as the rates' accuracy checks count them: one per angle unknown, two per slide along an
/// unknown angle, and a margin of two per unknown for each term whose angle sums unknowns.
#[test]
fn moving_columns_are_counted_from_the_loops() {
    let count = |declaration: proc_macro2::TokenStream| {
        let expansion = pretty(crate::expand::expand(declaration));
        let counts: std::collections::BTreeSet<String> = expansion
            .match_indices("T::constant(")
            .filter_map(|(at, _)| expansion[at..].split_once(')').map(|(call, _)| call))
            .filter(|call| call.ends_with("f64") && !call.contains('.'))
            .map(str::to_owned)
            .collect();
        counts.into_iter().collect::<Vec<_>>()
    };
    // A slide along a fixed line moves nothing; along an unknown angle, two columns.
    let slider = quote::quote! {
        pub struct Slider {
            params: l2, l3, c;
            input: theta2: angle;
            unknowns: theta3: angle, d: length;
            loop: l2 @ theta2 + l3 @ theta3 - c @ (pi / 2) - d @ 0;
            generate: position, velocity, acceleration;
        }
    };
    assert_eq!(count(slider), ["T::constant(1f64"]);
    let inverted = quote::quote! {
        pub struct Inverted {
            params: l1, l2;
            input: theta2: angle;
            unknowns: theta4: angle, b: length;
            loop: l2 @ theta2 - b @ theta4 - l1 @ 0;
            generate: position, velocity, acceleration;
        }
    };
    assert_eq!(count(inverted), ["T::constant(3f64"]);
    // An angle summing two unknowns: 2 for the angles, and 2·2 for the term.
    let summed = quote::quote! {
        pub struct Summed {
            params: l1, l2, l3, l4;
            input: theta2: angle;
            unknowns: theta3: angle, theta4: angle;
            loop: l2 @ theta2 + l3 @ (theta3 + theta4) - l4 @ theta4 - l1 @ 0;
            generate: position, velocity, acceleration;
        }
    };
    assert_eq!(count(summed), ["T::constant(6f64"]);
}

/// A four-bar whose coupler angle is measured the other way (`pi - phi3`, coefficient −1):
/// its closed forms solve for `phi3' = −phi3` and hand back `phi3 = −phi3'`, its unit vector
/// conjugated, and the scene kernel's block determinant changes sign with that column.
#[test]
fn flipped_angle_expansion() {
    let declaration = quote::quote! {
        /// Four-bar, the coupler's angle measured backwards.
        pub struct FourBarBackwards {
            params: l1, l2, l3, l4;
            input: theta2: angle;
            unknowns: phi3: angle, theta4: angle;
            loop: l2 @ theta2 + l3 @ (pi - phi3) - l4 @ theta4 - l1 @ 0;
            generate: position, velocity, acceleration, assemble;
            scene angles: phi3, theta4, phi3_dot, theta4_dot;
        }
    };
    let expansion = pretty(crate::expand::expand(declaration));
    assert!(expansion.contains("pub fn assemble"));
    assert_expansion("FourBarBackwards", &expansion);
}

/// Without a closed form, the struct's docs say which loop has none and why.
#[test]
fn docs_say_which_loop_has_no_closed_form() {
    let cases = [
        (
            quote::quote! {
                pub struct Chain {
                    params: l1, l2, l3, l4, l5, l6, l7, l8;
                    input: t: angle;
                    unknowns: a: angle, b: angle, c: angle, d: angle, e: angle, f: angle;
                    loop: l1 @ t + l2 @ a - l3 @ b - l1 @ 0;
                    loop: l4 @ b + l5 @ c + l6 @ d - l7 @ e - l8 @ 0;
                    loop: l4 @ a + l5 @ c - l6 @ d + l7 @ e - l8 @ f;
                }
            },
            "No closed form: loop 2 (`l4 @ b + l5 @ c + l6 @ d - l7 @ e - l8 @ 0`) has three \
             unknowns (`c`, `d` and `e`) left after loop 1 solved its own, more than its two \
             equations fix.",
        ),
        (
            quote::quote! {
                pub struct BothWays {
                    params: l1, l2, l3, e, l4;
                    input: theta2: angle;
                    unknowns: theta3: angle, theta4: angle;
                    loop: l2 @ theta2 + l3 @ theta3 + e @ (pi - theta3) - l4 @ theta4 - l1 @ 0;
                }
            },
            "- l1 @ 0`) turns vector 2 with `theta3` and vector 3 with `−theta3`: Chace's \
             cases need",
        ),
    ];
    for (declaration, expected) in cases {
        let expansion = pretty(crate::expand::expand(declaration));
        // The docs as one line, however they were wrapped.
        let docs: Vec<&str> = expansion
            .lines()
            .map_while(|line| line.trim().strip_prefix("///"))
            .map(str::trim)
            .collect();
        let docs = docs.join(" ");
        assert!(docs.contains(expected), "{docs}");
    }
}

/// Formulas of parameters: the ground from its pivot's coordinates, `hypot(gx, gy)` at
/// `atan2(gy, gx)`, computed with the other quantities of the dimensions alone (hoisted in
/// the general functions, once in `scenes()`), checked finite with the parameters, and
/// differentiated by the sensitivities.
#[test]
fn formula_expansion() {
    let declaration = quote::quote! {
        /// Four-bar, its ground pivot O4 at (gx, gy).
        pub struct FourBarFromPivot {
            params: gx, gy, l2, l3, l4;
            input: theta2: angle;
            unknowns: theta3: angle, theta4: angle;
            loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - hypot(gx, gy) @ atan2(gy, gx);
            generate: position, velocity, sensitivities;
            scene angles: theta3, theta4;
        }
    };
    let expansion = pretty(crate::expand::expand(declaration));
    assert!(expansion.contains("parameter formula `hypot(gx, gy)`"));
    assert!(expansion.contains(".atan2("));
    assert_expansion("FourBarFromPivot", &expansion);
}
