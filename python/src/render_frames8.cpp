// Renders from 8-bit frames (one unit per frame pixel type keeps each unit's compile cost down).
#include "render_tiles.hpp"

namespace mpr_py {
template void render_tiles<mpr::Rgb8, mpr::Rgb8>(const std::shared_ptr<const FrameSet8>&, const RenderJob&,
                                                 std::span<const Tile>, mpr::ImageView<mpr::Rgb8>);
template void render_tiles<mpr::Rgb8, mpr::Color>(const std::shared_ptr<const FrameSet8>&, const RenderJob&,
                                                  std::span<const Tile>, mpr::ImageView<mpr::Color>);
} // namespace mpr_py
