// Opt-in stb implementation for systems without Debian's libstb.
//
// mpr's headers only declare stb_image / stb_image_write. Where no compiled libstb exists,
// compile this file into exactly one target of your program (CMake: configure mpr with
// -DMPR_STB_IMPLEMENTATION=ON, which builds it as the library mpr::stb), with the stb headers
// on the include path.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
