// Renders from linear float frames.
#include "render_tiles.hpp"

namespace mpr_py {
template void render_tiles<mpr::Color, mpr::Rgb8>(const std::shared_ptr<const FrameSetLinear>&, const RenderJob&,
                                                  std::span<const Tile>, mpr::ImageView<mpr::Rgb8>);
template void render_tiles<mpr::Color, mpr::Color>(const std::shared_ptr<const FrameSetLinear>&, const RenderJob&,
                                                   std::span<const Tile>, mpr::ImageView<mpr::Color>);
} // namespace mpr_py
