/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include "LazyModule.h"

#include <osgDB/FileNameUtils>

#include <dlfcn.h>

#include <map>
#include <mutex>
#include <stdexcept>

namespace osgLoA
{

void* lazyModuleSymbol(const std::string& module, const char* symbol)
{
    static std::mutex mutex;
    static std::map<std::string, void*> handles;
    std::lock_guard<std::mutex> lock(mutex);
    void*& handle = handles[module];
    // Beside libosgLoA (the build tree's lib/, or the installed libdir).
    auto path = [&]
    {
        Dl_info info;
        std::string dir;
        if (dladdr(reinterpret_cast<void*>(&lazyModuleSymbol), &info) && info.dli_fname)
            dir = osgDB::getFilePath(info.dli_fname);
        return (dir.empty() ? std::string() : dir + "/") + "lib" + module + ".so";
    };
    if (!handle)
    {
        handle = dlopen(path().c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle)
        {
            const char* e = dlerror();
            throw std::runtime_error("cannot load osgLoA's module '" + path() +
                                     "': " + (e ? e : "unknown reason"));
        }
    }
    void* f = dlsym(handle, symbol);
    if (!f) throw std::runtime_error("osgLoA's module '" + path() + "' lacks " + symbol);
    return f;
}

} // namespace osgLoA
