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
