#include "CityGmlPrescan.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <sys/stat.h>

namespace citygmlimport
{
namespace
{
bool isSpace(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/** The local name of a tag's text ("gml:posList attr=..." -> "posList"). */
std::string localName(const std::string& tag)
{
    std::size_t end = 0;
    while (end < tag.size() && !isSpace(tag[end]) && tag[end] != '/')
        ++end;
    const std::string qualified = tag.substr(0, end);
    const std::size_t colon = qualified.find(':');
    return colon == std::string::npos ? qualified : qualified.substr(colon + 1);
}
} // namespace

PrescanResult prescan(const std::string& path, const std::string& label, const osgLoA::InputLimits& limits)
{
    using osgLoA::InputLimitError;
    using osgLoA::InputLimits;
    struct stat st;
    if (::stat(path.c_str(), &st) != 0)
        throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw std::runtime_error("not a regular file (a device, FIFO or folder)");
    if (static_cast<std::uint64_t>(st.st_size) > limits.maxFileBytes)
        throw InputLimitError(InputLimits::exceeded(
            label, "a file of " + std::to_string(st.st_size) + " bytes", "max-file", limits.maxFileBytes));
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    struct Closer
    {
        std::FILE* f;
        ~Closer() { std::fclose(f); }
    } closer{f};

    enum State
    {
        Text,
        Tag,  // after '<', up to '>' (quotes tracked)
        Skip, // comment, CDATA, processing instruction, declaration: up to `terminator`
    } state = Text;
    PrescanResult r;
    std::string tag, terminator, tail;
    char quote = 0;
    unsigned depth = 0;
    bool inList = false, inNumber = false;
    std::uint64_t listNumbers = 0;
    const std::uint64_t maxCoordinates = limits.maxVertices * 3;
    const std::uint64_t maxListNumbers = std::uint64_t(limits.maxRingVertices) * 3;
    char buffer[1 << 16];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0)
        for (std::size_t i = 0; i < n; ++i)
        {
            const char c = buffer[i];
            switch (state)
            {
            case Text:
                if (c == '<')
                {
                    state = Tag, tag.clear(), quote = 0;
                    inNumber = false;
                }
                else if (inList)
                {
                    const bool numberChar = !isSpace(c);
                    if (numberChar && !inNumber)
                    {
                        ++r.coordinates, ++listNumbers;
                        if (listNumbers > maxListNumbers)
                            throw InputLimitError(InputLimits::exceeded(
                                label,
                                "a gml:posList of more than " + std::to_string(limits.maxRingVertices) +
                                    " vertices",
                                "max-ring-vertices", limits.maxRingVertices));
                        if (r.coordinates > maxCoordinates)
                            throw InputLimitError(InputLimits::exceeded(
                                label, "more than " + std::to_string(limits.maxVertices) + " vertices",
                                "max-vertices", limits.maxVertices));
                    }
                    inNumber = numberChar;
                }
                break;
            case Skip:
                tail.push_back(c);
                if (tail.size() > terminator.size()) tail.erase(0, 1);
                if (tail == terminator) state = Text;
                break;
            case Tag:
                if (quote)
                {
                    if (c == quote) quote = 0;
                    if (tag.size() < 256) tag.push_back(c);
                    break;
                }
                if (tag.empty() && (c == '?' || c == '!'))
                {
                    tag.push_back(c);
                    break;
                }
                if (tag == "!" && c == '-')
                {
                    state = Skip, terminator = "-->", tail = "!-";
                    break;
                }
                if (tag == "!" && c == '[')
                {
                    state = Skip, terminator = "]]>", tail.clear();
                    break;
                }
                if (tag == "?")
                {
                    state = Skip, terminator = "?>", tail = std::string(1, c);
                    break;
                }
                if (c == '"' || c == '\'')
                {
                    quote = c;
                    if (tag.size() < 256) tag.push_back(c);
                    break;
                }
                if (c != '>')
                {
                    // Only the start of a tag matters (its name, '/' first or last).
                    if (tag.size() < 256)
                        tag.push_back(c);
                    else
                        tag.back() = c;
                    break;
                }
                state = Text;
                if (tag.empty() || tag[0] == '!') break; // a declaration such as <!DOCTYPE ...>
                if (tag[0] == '/')
                {
                    if (depth > 0) --depth;
                    if (inList) inList = false;
                    break;
                }
                ++r.elements;
                if (tag.back() == '/') break; // <empty/>
                if (++depth > limits.maxDepth)
                    throw InputLimitError(InputLimits::exceeded(
                        label, "XML nested deeper than " + std::to_string(limits.maxDepth) + " elements",
                        "max-depth", limits.maxDepth));
                if (depth > r.maxDepth) r.maxDepth = depth;
                {
                    const std::string name = localName(tag);
                    inList = name == "posList" || name == "pos" || name == "coordinates";
                    if (inList)
                    {
                        if (listNumbers > r.longestList) r.longestList = listNumbers;
                        listNumbers = 0;
                    }
                }
                break;
            }
        }
    if (listNumbers > r.longestList) r.longestList = listNumbers;
    if (std::ferror(f)) throw std::runtime_error("cannot read the file");
    return r;
}

} // namespace citygmlimport
