#pragma once
/// \file
/// Umbrella header of mpr's camera-array light fields: calibrated frames, the frame table, the
/// camera-frame ray sampler with its interpolations (one header each), and the loaders of real
/// data formats.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/camera/pinhole_glc.hpp>
#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/io/depth_maps.hpp>
#include <mpr/io/hci_light_field.hpp>
#include <mpr/io/hci_parameters.hpp>
#include <mpr/io/lfca_calibration.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/io/pfm.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/lightfield/array_disparity.hpp>
#include <mpr/lightfield/array_plane.hpp>
#include <mpr/lightfield/array_view.hpp>
#include <mpr/lightfield/camera_index.hpp>
#include <mpr/lightfield/cylinder_aperture.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/disparity_score.hpp>
#include <mpr/lightfield/frame_prefilter.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/nearest_camera.hpp>
#include <mpr/lightfield/synthetic_aperture.hpp>
#include <mpr/lightfield/view_depth.hpp>
#include <mpr/lightfield/visual_hull.hpp>
