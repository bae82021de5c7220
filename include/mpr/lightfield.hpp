#pragma once
/// \file
/// Umbrella header of mpr's camera-array light fields: calibrated frames, the camera-frame ray
/// sampler with its interpolation policies, and the loaders of real data formats.

#include <mpr/io/lfca_calibration.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/lightfield/camera_index.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/frame_set.hpp>
