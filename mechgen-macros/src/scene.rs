//! Scenes: what one caller needs from the mechanism, down to single outputs.
//!
//! `scene trace: coupler, coupler_dot;` names an unknown or a point for its value, with
//! `_dot` for its rate and `_ddot` for its acceleration. Each scene becomes one generated
//! kernel that computes exactly those outputs and nothing a caller did not ask for.

use std::collections::{BTreeMap, BTreeSet};

use syn::ext::IdentExt;
use syn::{Attribute, Ident};

use crate::errors::Errors;

/// A declared scene, resolved.
pub struct Scene {
    pub name: Ident,
    pub docs: Vec<Attribute>,
    /// The outputs in the order written, which is the order of the output struct's fields.
    pub items: Vec<SceneItem>,
}

/// One output of a scene: a field of its output struct.
pub struct SceneItem {
    /// The name as written (`coupler_dot`), which names the field.
    pub field: Ident,
    pub quantity: Quantity,
    pub order: Order,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    Unknown(usize),
    Point(usize),
}

/// Which time derivative of a quantity: its value, rate or acceleration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Order {
    Value,
    Rate,
    Acceleration,
}

impl Scene {
    /// The highest derivative any output needs, which decides what the kernel solves for and
    /// which input rates it takes.
    pub fn order(&self) -> Order {
        self.items
            .iter()
            .map(|item| item.order)
            .max()
            .unwrap_or(Order::Value)
    }
}

/// What a declared name names, for the rule that the names a scene lists are unique.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Declared {
    Param,
    Input,
    Unknown,
    Point,
}

impl Declared {
    fn noun(self) -> &'static str {
        match self {
            Declared::Param => "parameter",
            Declared::Input => "input",
            Declared::Unknown => "unknown",
            Declared::Point => "point",
        }
    }

    /// The names a scene reads as this declaration's: an unknown's or a point's value, rate
    /// and acceleration (`x`, `x_dot`, `x_ddot`, see [`item`]); a parameter's or an input's
    /// own name, which a scene cannot list but which must not name an output either.
    fn scene_names(self, name: &str) -> Vec<(String, Order)> {
        match self {
            Declared::Param | Declared::Input => vec![(name.to_string(), Order::Value)],
            Declared::Unknown | Declared::Point => vec![
                (name.to_string(), Order::Value),
                (format!("{name}_dot"), Order::Rate),
                (format!("{name}_ddot"), Order::Acceleration),
            ],
        }
    }
}

/// Rule: every name a scene can list means one thing. A scene reads `x`, `x_dot` and
/// `x_ddot` as an unknown's or a point's value, rate and acceleration, so a point `theta4`
/// beside the unknown `theta4`, a point `theta3_dot` beside the unknown `theta3`, or points
/// `p` and `p_dot` would make a scene silently return one of the two; and an output named
/// like a parameter or an input would read as that. Each clash is reported at the later
/// declaration, naming the earlier one. The same name declared twice as parameters, input
/// or unknowns, or as two points, is reported where those are resolved, and not again here;
/// parameters and inputs are not outputs, so their names may meet (a parameter `theta_dot`
/// beside the input `theta`).
///
/// `declared` lists every declared name in the order written.
pub fn check_unambiguous(declared: &[(Declared, Ident)], errors: &mut Errors) {
    // Each name a scene could read, with the first declaration that gives it.
    let mut owners: BTreeMap<String, (usize, Order)> = BTreeMap::new();
    for (index, &(what, ref name)) in declared.iter().enumerate() {
        let text = name.unraw().to_string();
        let mut reported = false;
        for (scene_name, order) in what.scene_names(&text) {
            let Some(&(earlier, earlier_order)) = owners.get(&scene_name) else {
                owners.insert(scene_name, (index, order));
                continue;
            };
            let (earlier_what, earlier_name) = &declared[earlier];
            let declared_twice = earlier_name.unraw() == text
                && (what == Declared::Point) == (*earlier_what == Declared::Point);
            if reported || declared_twice {
                continue;
            }
            reported = true;
            let role = |order: Order, noun: String| match order {
                Order::Value => noun,
                Order::Rate => format!("the rate of {noun}"),
                Order::Acceleration => format!("the acceleration of {noun}"),
            };
            let noun = what.noun();
            let earlier_noun = earlier_what.noun();
            errors.error_at(
                name,
                format!(
                    "{noun} `{name}` clashes with the {earlier_noun} `{earlier_name}` declared \
                     before it: in a scene, `{scene_name}` would name both {} and {}; rename \
                     one of them",
                    role(order, format!("this {noun}")),
                    role(
                        earlier_order,
                        format!("the {earlier_noun} `{earlier_name}`")
                    ),
                ),
            );
        }
    }
}

/// Names a scene may not take: they would collide with the generated types
/// (`{Name}Unknowns`, `{Name}Points`, `{Name}Scenes`) or the scenes type's own method.
const RESERVED: [&str; 4] = ["unknowns", "points", "scenes", "mechanism"];

/// What the scene resolver can see of the model.
pub struct Names<'a> {
    pub params: &'a [Ident],
    /// The driven inputs: a scene kernel takes one.
    pub inputs: &'a [Ident],
    pub unknowns: &'a [Ident],
    pub points: &'a [Ident],
}

/// Resolves every scene; reports unknown, repeated and misplaced names.
pub fn resolve(
    declared: Vec<(Vec<Attribute>, Ident, Vec<Ident>)>,
    names: &Names,
    errors: &mut Errors,
) -> Vec<Scene> {
    let mut scene_names = BTreeSet::new();
    declared
        .into_iter()
        .map(|(docs, name, outputs)| {
            let text = name.unraw().to_string();
            if RESERVED.contains(&text.as_str()) || text.ends_with("_batch") {
                errors.error_at(
                    &name,
                    format!(
                        "`{name}` names a generated item already (each scene `s` also makes \
                         `s_batch`): call the scene otherwise"
                    ),
                );
            } else if !scene_names.insert(text) {
                errors.error_at(&name, format!("scene `{name}` is declared twice"));
            }
            if names.inputs.len() > 1 {
                errors.error_at(
                    &name,
                    "scenes are kernels of one input, and this mechanism has several: use the \
                     general functions (`motion`, `points`, ...), which take every input",
                );
            }
            let mut fields = BTreeSet::new();
            let items = outputs
                .into_iter()
                .filter_map(|field| {
                    if !fields.insert(field.unraw().to_string()) {
                        errors.error_at(&field, format!("`{field}` is listed twice in this scene"));
                        return None;
                    }
                    match item(&field, names) {
                        Ok((quantity, order)) => Some(SceneItem {
                            field,
                            quantity,
                            order,
                        }),
                        Err(message) => {
                            errors.error_at(&field, message);
                            None
                        }
                    }
                })
                .collect();
            Scene { name, docs, items }
        })
        .collect()
}

/// What `field` asks for, or why it cannot be a scene output.
fn item(field: &Ident, names: &Names) -> Result<(Quantity, Order), String> {
    let text = field.unraw().to_string();
    let find = |stem: &str| {
        let position = |list: &[Ident]| list.iter().position(|n| n.unraw() == stem);
        position(names.unknowns)
            .map(Quantity::Unknown)
            .or_else(|| position(names.points).map(Quantity::Point))
    };
    // `_ddot` before `_dot`: `x_ddot` also ends in `dot`.
    let candidates = [
        (text.as_str(), Order::Value),
        (
            text.strip_suffix("_ddot").unwrap_or(""),
            Order::Acceleration,
        ),
        (text.strip_suffix("_dot").unwrap_or(""), Order::Rate),
    ];
    for (stem, order) in candidates {
        if let Some(quantity) = (!stem.is_empty()).then(|| find(stem)).flatten() {
            return Ok((quantity, order));
        }
    }
    let stem = candidates
        .iter()
        .skip(1)
        .map(|(stem, _)| *stem)
        .find(|stem| !stem.is_empty())
        .unwrap_or(&text);
    if let Some(input) = names.inputs.iter().find(|input| input.unraw() == stem) {
        return Err(format!(
            "the input `{input}` and its rates are the scene's arguments, not its outputs"
        ));
    }
    if names.params.iter().any(|p| p.unraw() == stem) {
        return Err(format!(
            "`{stem}` is a parameter, a constant of the mechanism: a scene lists unknowns and points"
        ));
    }
    let list = |idents: &[Ident]| {
        if idents.is_empty() {
            "none".to_string()
        } else {
            idents
                .iter()
                .map(|i| format!("`{}`", i.unraw()))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    Err(format!(
        "`{field}` is not an output of this mechanism: a scene lists unknowns ({}) and points \
         ({}), each as its name for the value, `_dot` for its rate, `_ddot` for its acceleration",
        list(names.unknowns),
        list(names.points),
    ))
}

#[cfg(test)]
mod tests {
    use super::{Declared, check_unambiguous};
    use crate::errors::Errors;

    fn clashes(declared: &[(Declared, &str)]) -> bool {
        let declared: Vec<_> = declared
            .iter()
            .map(|&(what, name)| (what, syn::Ident::new(name, proc_macro2::Span::call_site())))
            .collect();
        let mut errors = Errors::default();
        check_unambiguous(&declared, &mut errors);
        !errors.is_empty()
    }

    #[test]
    fn a_scene_name_that_could_mean_two_things_is_a_clash() {
        use Declared::*;
        assert!(clashes(&[(Unknown, "theta3"), (Point, "theta3_dot")]));
        assert!(clashes(&[(Point, "p_ddot"), (Point, "p")]));
        assert!(clashes(&[(Unknown, "theta4"), (Point, "theta4")]));
        assert!(clashes(&[(Param, "l1"), (Point, "l1")]));
        assert!(clashes(&[(Input, "q_dot"), (Unknown, "q")]));
        // Not outputs, or outputs whose names never meet.
        assert!(!clashes(&[(Param, "theta_dot"), (Input, "theta")]));
        assert!(!clashes(&[
            (Unknown, "x"),
            (Unknown, "x_d"),
            (Point, "x_dd")
        ]));
        assert!(!clashes(&[(Param, "l1"), (Point, "l1_dot")]));
        // Declared twice: reported where the names are resolved, not here.
        assert!(!clashes(&[(Param, "a"), (Unknown, "a")]));
        assert!(!clashes(&[(Point, "p"), (Point, "p")]));
    }
}
