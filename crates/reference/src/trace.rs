//! The light that arrives along one ray: a path traced through the scene,
//! gathering at each surface the light sent by the lights (next-event
//! estimation) and following one reflected direction (drawn from the
//! surface's reflection). A light met by a reflected direction counts with
//! the weight multiple importance sampling (the power heuristic) gives it,
//! so light that either strategy finds is counted once. Russian roulette
//! ends dim paths, and weights those it keeps by as much.

use glam::Vec3;

use crate::geometry::{Ray, SURFACE_OFFSET};
use crate::material::Bsdf;
use crate::sampler::Sampler;
use crate::scene::{Hit, Scene};

/// Bounces before Russian roulette may end a path.
const ROULETTE_AFTER: u32 = 3;
/// The most a path survives the roulette with: 1 would let a path between
/// two white surfaces run on for ever.
const MOST_SURVIVAL: f32 = 0.95;

/// Veach's power heuristic (exponent 2): the weight of a strategy that
/// drew a direction with density `a`, beside one with density `b`.
fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// The radiance arriving along `ray`, one path's estimate.
pub fn radiance(scene: &Scene, ray: Ray, rng: &mut Sampler) -> Vec3 {
    let mut ray = ray;
    let mut total = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    // The density the last reflection drew this ray's direction with;
    // none for the camera's ray, which no light sample could have drawn.
    let mut last_pdf: Option<f32> = None;
    let lights = scene.lights();
    let light_choice = 1.0 / lights.len().max(1) as f32;
    for bounce in 0.. {
        let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
            break;
        };
        let material = scene.material_of(hit.material);
        if material.emission != Vec3::ZERO {
            let weight = match (last_pdf, hit.light) {
                (Some(pdf), Some(light)) => {
                    power_heuristic(pdf, light_choice * lights[light as usize].pdf(ray.origin))
                }
                _ => 1.0,
            };
            total += throughput * material.emission * weight;
        }
        if hit.light.is_some() {
            // Lights are black: they glow, and reflect nothing.
            break;
        }
        let bsdf = Bsdf::new(scene.albedo(&hit), material.finish, hit.normal);
        let outgoing = -ray.dir;
        let origin = hit.point + hit.normal * SURFACE_OFFSET;
        if !lights.is_empty() {
            total +=
                throughput * light_sent(scene, &bsdf, &hit, origin, outgoing, light_choice, rng);
        }
        let Some(next) = bsdf.sample(outgoing, rng) else {
            break;
        };
        throughput *= next.value * next.dir.dot(hit.normal).max(0.0) / next.pdf;
        if bounce >= ROULETTE_AFTER {
            let survival = throughput.max_element().min(MOST_SURVIVAL);
            if rng.uniform() >= survival {
                break;
            }
            throughput /= survival;
        }
        last_pdf = Some(next.pdf);
        ray = Ray {
            origin,
            dir: next.dir,
        };
    }
    total
}

/// The light one light, chosen at random, sends to `hit` and on towards
/// `outgoing`, weighed against finding it by reflection.
fn light_sent(
    scene: &Scene,
    bsdf: &Bsdf,
    hit: &Hit,
    origin: Vec3,
    outgoing: Vec3,
    light_choice: f32,
    rng: &mut Sampler,
) -> Vec3 {
    let lights = scene.lights();
    let pick = ((rng.uniform() * lights.len() as f32) as usize).min(lights.len() - 1);
    let light = &lights[pick];
    let Some(sample) = light.sample(origin, rng) else {
        return Vec3::ZERO;
    };
    let cos = sample.dir.dot(hit.normal);
    if cos <= 0.0 {
        return Vec3::ZERO;
    }
    let value = bsdf.value(outgoing, sample.dir);
    if value == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let shadow = Ray {
        origin,
        dir: sample.dir,
    };
    // Stop short of the light's own surface: the light is not its shadow.
    if !scene.clear(&shadow, sample.distance * (1.0 - 1e-4)) {
        return Vec3::ZERO;
    }
    let pdf = light_choice * sample.pdf;
    let weight = power_heuristic(pdf, bsdf.pdf(outgoing, sample.dir));
    value * cos * light.radiance * weight / pdf
}
