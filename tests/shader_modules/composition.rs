//! Every entry shader composes and validates in the variants it is specialized in (every
//! material key on the mesh and camera where the most defs meet, the covering keys on the
//! others: see `variants`), and every module of the crate, composed alone (all its
//! functions, used or not), with the covering keys' combinations of the crate's defs. A WESL
//! error in a branch no render test draws fails here, with the variants it breaks and the
//! defs they share.

use crate::{
    library::{
        CONSTANT_COLOR, CONTRACT_KERNEL, PHONG_MATERIAL, PHONG_PREPASS, PHONG_PREPASS_VERTEX,
        PHONG_VERTEX, SEARCHLIGHT, SHADOW_CASTER, SURFACE_INPUTS, library,
    },
    variants::{self, Variant},
};
use bevy::shader::ShaderDefVal;
use std::{collections::BTreeSet, time::Instant};

/// Failing variants listed by name before the rest are only counted.
const LISTED_FAILURES: usize = 8;

/// Composes and validates `path` in each of `variants`; panics with the variants that fail,
/// the defs they all have and some passing variant lacks, and the first error in full.
fn assert_every_variant_validates(path: &str, variants: &[Variant]) {
    let start = Instant::now();
    let library = library();
    let (failed, passed): (Vec<_>, Vec<_>) = variants
        .iter()
        .map(|variant| (variant, library.compose(path, &variant.defs).err()))
        .partition(|(_, error)| error.is_some());
    println!(
        "{path}: {} variants composed and validated in {:.2} s, {} failed",
        variants.len(),
        start.elapsed().as_secs_f64(),
        failed.len()
    );
    let Some((first, Some(error))) = failed.first() else {
        return;
    };
    let names: Vec<&str> = failed
        .iter()
        .take(LISTED_FAILURES)
        .map(|(variant, _)| variant.name.as_str())
        .collect();
    let common = |group: &[(&Variant, Option<String>)]| -> BTreeSet<String> {
        group
            .iter()
            .map(|(variant, _)| variant.defs.iter().map(def_name).collect::<BTreeSet<_>>())
            .reduce(|all, defs| &all & &defs)
            .unwrap_or_default()
    };
    let in_every_passing = common(&passed);
    let suspects: BTreeSet<String> = &common(&failed) - &in_every_passing;
    panic!(
        "{path}: {} of {} variants fail, among them {names:#?}\n\
         defs every failing variant has (and not every passing one): {suspects:?}\n\
         the first ({}):\n{error}",
        failed.len(),
        variants.len(),
        first.name
    );
}

/// A def's name, `!NAME` for a flag set off (as the WebGL2 device's `PHONG_STORAGE_BUFFERS`).
fn def_name(def: &ShaderDefVal) -> String {
    match def {
        ShaderDefVal::Bool(name, false) => format!("!{name}"),
        ShaderDefVal::Bool(name, true)
        | ShaderDefVal::Int(name, _)
        | ShaderDefVal::UInt(name, _) => name.to_string(),
    }
}

#[test]
fn every_module_of_the_crate_validates_whole_with_each_of_its_defs_on_and_off() {
    let library = library();
    let modules = library.crate_modules();
    assert!(modules.len() >= 6, "the crate's modules: {modules:?}");
    let variants = variants::covering_def_sets();
    for def in variants::every_crate_def() {
        let has = |variant: &Variant| variant.defs.iter().any(|set| def_name(set) == def);
        assert!(
            variants.iter().any(has) && !variants.iter().all(has),
            "{def} is on in some set of the covering keys' defs and off in another"
        );
    }
    for module in modules {
        assert_every_variant_validates(module, &variants);
    }
}

#[test]
fn every_phong_material_variant_validates() {
    assert_every_variant_validates(PHONG_MATERIAL, &variants::phong_material());
}

#[test]
fn every_phong_prepass_variant_validates() {
    assert_every_variant_validates(PHONG_PREPASS, &variants::phong_prepass());
}

#[test]
fn every_displaced_vertex_variant_validates() {
    assert_every_variant_validates(PHONG_VERTEX, &variants::displaced_vertex(false));
    assert_every_variant_validates(PHONG_PREPASS_VERTEX, &variants::displaced_vertex(true));
}

#[test]
fn every_vertex_lit_vertex_variant_validates() {
    assert_every_variant_validates(PHONG_VERTEX, &variants::vertex_lit_vertex());
}

#[test]
fn every_searchlight_variant_validates() {
    assert_every_variant_validates(SEARCHLIGHT, &variants::phong_extension());
}

#[test]
fn every_surface_inputs_and_constant_color_variant_validates() {
    assert_every_variant_validates(SURFACE_INPUTS, &variants::plain_material());
    assert_every_variant_validates(CONSTANT_COLOR, &variants::plain_material());
}

#[test]
fn the_shadow_caster_and_the_contract_kernel_validate() {
    assert_every_variant_validates(SHADOW_CASTER, &variants::shadow_caster());
    assert_every_variant_validates(CONTRACT_KERNEL, &variants::without_defs());
}
