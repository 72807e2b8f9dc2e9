/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#ifndef OSGLOA_UTIL_LAZYMODULE_H
#define OSGLOA_UTIL_LAZYMODULE_H 1

#include <string>

namespace osgLoA
{

/** A function of one of libosgLoA's modules (libosgLoA_imageio.so: OpenImageIO, libosgLoA_gdal.so:
 *  GDAL), loaded beside libosgLoA the first time it is asked for: libraries with hundreds of
 *  dependencies cost every process that links them at start, whether it uses them or not
 *  (OpenImageIO 0.4 s, GDAL 0.08 s). Thread-safe; a module is opened once. Throws
 *  std::runtime_error naming the module's path and the loader's reason when it cannot be loaded
 *  or lacks the symbol. */
void* lazyModuleSymbol(const std::string& module, const char* symbol);

} // namespace osgLoA

#endif
