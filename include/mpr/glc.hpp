#pragma once
/// \file
/// General Linear Cameras (Yu & McMillan, ECCV 2004; Yu & McMillan, ICCV 2005; Adams & Levoy,
/// EGSR 2007): two-plane form, characteristic equation, classification, projection, canonical
/// cameras, the nine gallery views and rectification. See docs/glc.md.

#include <mpr/glc/aperture.hpp>
#include <mpr/glc/cameras.hpp>
#include <mpr/glc/characteristic.hpp>
#include <mpr/glc/classify.hpp>
#include <mpr/glc/finite_aperture.hpp>
#include <mpr/glc/focus.hpp>
#include <mpr/glc/gallery.hpp>
#include <mpr/glc/project.hpp>
#include <mpr/glc/rectify.hpp>
#include <mpr/glc/two_plane.hpp>
#include <mpr/surface/homography_surface.hpp>
