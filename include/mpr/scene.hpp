#pragma once
/// \file
/// Umbrella header for synthetic scenes: the scene model, shape builders, the demo classroom, the
/// BVH ray caster (`mpr::SceneSampler<Scene, mpr::RayCast>`), the software rasterizer and the
/// rasterized virtual camera array (`mpr::SceneSampler<Scene, mpr::Rasterized<...>>`).
/// OBJ loading needs tinyobjloader and lives apart, in <mpr/scene/obj_loader.hpp>.

#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/rasterized_sampler.hpp>
#include <mpr/scene/rasterizer.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/scene_sampler.hpp>
#include <mpr/scene/shapes.hpp>
#include <mpr/scene/texture.hpp>
