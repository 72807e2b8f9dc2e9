// libFuzzer target: arbitrary bytes as a filter-cache file (.loafc, FilterCache's format: a
// header, level sizes, RGBA8 texels, an FNV-1a checksum), the image data the texture tools read
// back from disk (issue 22 item 5, "the image paths"). Each input is decoded twice: as it is,
// for the key its header names; and with its checksum recomputed here (an independent FNV-1a),
// so that the fuzzer gets past the checksum to the size and level fields. A decode must refuse
// with a reason or give a pyramid that encodes back to exactly the bytes decoded.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=FilterCacheFuzzer). Seed corpus:
// tests/fuzz/corpus/filtercache.
#include <osgLoA/filtering/FilterCache>

#include <osg/Notify>

#include "FuzzSupport.h"

#include <cstdint>
#include <cstring>
#include <string>

namespace
{
const char* const kTarget = "FilterCacheFuzzer";

std::uint64_t fnv1a64(const unsigned char* p, std::size_t n)
{
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

std::uint64_t le64(const std::string& b, std::size_t at)
{
    std::uint64_t v = 0;
    for (int k = 7; k >= 0; --k)
        v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(k)]);
    return v;
}

void decodeOnce(const std::string& bytes)
{
    osgLoA::FilterCacheKey key;
    if (bytes.size() >= 32) key.high = le64(bytes, 16), key.low = le64(bytes, 24);
    std::string why;
    osg::ref_ptr<osg::Image> pyramid = osgLoA::FilterCache::decode(bytes, key, why);
    if (!pyramid)
    {
        if (why.empty()) fuzz::fail(kTarget, "a refusal without a reason");
        return;
    }
    if (pyramid->s() < 1 || pyramid->t() < 1 || !pyramid->data())
        fuzz::fail(kTarget, "an empty pyramid decoded");
    if (osgLoA::FilterCache::encode(key, *pyramid) != bytes)
        fuzz::fail(kTarget, "the decoded pyramid does not encode back to the same bytes");
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::string bytes(reinterpret_cast<const char*>(data), size);
    decodeOnce(bytes);
    if (bytes.size() >= 48)
    {
        const std::uint64_t sum =
            fnv1a64(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size() - 8);
        for (int k = 0; k < 8; ++k)
            bytes[bytes.size() - 8 + static_cast<std::size_t>(k)] =
                static_cast<char>((sum >> (8 * k)) & 0xff);
        decodeOnce(bytes);
    }
    return 0;
}
