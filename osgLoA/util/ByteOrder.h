// Private: little-endian integers in byte strings (the cache file formats).
#ifndef OSGLOA_UTIL_BYTEORDER_H
#define OSGLOA_UTIL_BYTEORDER_H 1

#include <cstdint>
#include <string>

namespace osgLoA
{
namespace detail
{

/** Appends the low `bytes` bytes of v, least significant first. */
inline void putLE(std::string& s, std::uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; ++i)
        s.push_back(char((v >> (8 * i)) & 0xffu));
}

/** Reads `bytes` bytes at `at`, least significant first (the caller checks the length). */
inline std::uint64_t getLE(const std::string& s, std::size_t at, int bytes)
{
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i)
        v = (v << 8) | static_cast<unsigned char>(s[at + std::size_t(i)]);
    return v;
}

} // namespace detail
} // namespace osgLoA

#endif
