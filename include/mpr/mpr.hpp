#pragma once
/// \file
/// Umbrella header: the core, the GLC module, the scene module, the light-field module and the
/// sampling module -- everything in mpr that needs no optional dependency (the OBJ loader, which
/// needs tinyobjloader, is included separately: <mpr/scene/obj_loader.hpp>).

#include <mpr/core/color.hpp>
#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/image_metrics.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/core/region.hpp>
#include <mpr/render/renderer.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/glc.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/lightfield.hpp>
#include <mpr/sampling.hpp>
#include <mpr/scene.hpp>
#include <mpr/scene/checkerboard_plane.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>
