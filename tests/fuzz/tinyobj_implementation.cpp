// tinyobjloader's implementation, compiled into the fuzz targets with their instrumentation.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
