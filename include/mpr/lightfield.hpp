#pragma once
/// \file
/// Umbrella header of mpr's camera-array light fields: calibrated frames, the camera-frame ray
/// sampler with its interpolation policies, and the loaders of real data formats.

#include <mpr/io/lfca_calibration.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/io/planar_camera_array.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/sampler/camera_frame_index.hpp>
#include <mpr/sampler/camera_frame_interpolation.hpp>
#include <mpr/sampler/camera_frame_sampler.hpp>
#include <mpr/sampler/camera_frame_set.hpp>
