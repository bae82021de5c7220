#pragma once
/// \file
/// Umbrella header of the sampling module: pixel-sampling policies of `mpr::Renderer`
/// (`PixelCentre`, `Supersample<Stratified | OwenSobol, Filter>`) and reconstruction filters
/// (box, tent, Gaussian, Mitchell-Netravali, Lanczos, and `AnyFilter` chosen at run time).

#include <mpr/sampling/any_filter.hpp>
#include <mpr/sampling/filters.hpp>
#include <mpr/sampling/pixel_sampling.hpp>
#include <mpr/sampling/sobol.hpp>
#include <mpr/sampling/stratified.hpp>
