/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include "BoundedInputIterator.h"

#include <osgLoA/util/BoundedObjectReader>

#include <osg/Endian>
#include <osg/Image>
#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/Registry>
#include <osgDB/Serializer>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace osgLoA
{
namespace detail
{

// --- SharedIds ----------------------------------------------------------------------------------

std::string SharedIds::image(std::uint64_t id, const std::string& className, bool& isNew)
{
    const auto found = _classes.find(id);
    isNew = found == _classes.end();
    if (isNew)
    {
        _classes.emplace(id, className);
        return std::string();
    }
    const std::string& name = found->second;
    if (name == "osg::Image") return std::string();
    if (osgDB::ObjectWrapper* w = osgDB::Registry::instance()->getObjectWrapperManager()->findWrapper(name))
        for (const osgDB::ObjectWrapperAssociate& a : w->getAssociates())
            if (a._name == "osg::Image") return std::string();
    return "UniqueID " + std::to_string(id) + " names the " + name + " read before, where an image belongs";
}

// --- BoundedInputIterator -----------------------------------------------------------------------

void BoundedInputIterator::fail(const std::string& what)
{
    // OSG goes on reading after a serializer failed (InputStream::throwException: "SaliencyMetric:
    // unknown Kind '7'"), out of step with the data: the failure it recorded (the last, if
    // several) names the file's problem, not the nonsense read after it (a string field read
    // from the middle of a number).
    if (const osgDB::InputException* e = _inputStream ? _inputStream->getException() : nullptr)
    {
        const std::string where = e->getField();
        throw MalformedFileError(e->getError() + (where.empty() ? std::string() : " (at " + where + ")"));
    }
    throw MalformedFileError(at() + ": " + what);
}

BoundedInputIterator::IdState BoundedInputIterator::beginRead()
{
    const IdState before = _idState;
    _idState = IdState::None;
    _count = kNoCount;
    return before;
}

BoundedInputIterator::Expected BoundedInputIterator::takeExpected()
{
    Expected e;
    std::swap(e, _expected);
    return e;
}

void BoundedInputIterator::afterString(IdState before, const std::string& s)
{
    _idState = before == IdState::ClassNameProperty ? IdState::ImageClass : IdState::String;
    _className = s;
}

void BoundedInputIterator::afterProperty(IdState before, const std::string& name)
{
    if (name == "ClassName")
        _idState = IdState::ClassNameProperty;
    else if (name == "UniqueID")
    {
        _idState = before == IdState::ObjectBrace ? IdState::ObjectId : IdState::ImageId;
        if (_idState == IdState::ImageId && before != IdState::ImageClass)
            _className = "osg::Image"; // files before version 95 name no image class
    }
    else
        _idState = IdState::None;
}

void BoundedInputIterator::afterInteger(IdState before, const Expected& expected, std::uint64_t value)
{
    _count = value;
    if (expected.entryBytes > 0 && value * expected.entryBytes > remaining())
        fail(std::to_string(value) + " entries of " + std::to_string(expected.entryBytes) +
             " bytes stated for '" + expected.name + "', with " + std::to_string(remaining()) +
             " bytes left in the data");
    if (before == IdState::ObjectId) _ids.object(value, _className);
    _newImage = false;
    if (before == IdState::ImageId)
        if (const std::string bad = _ids.image(value, _className, _newImage); !bad.empty()) fail(bad);
}

void BoundedInputIterator::openMark(IdState before, std::uint64_t count, std::uint64_t room)
{
    if (++_depth > BoundedObjectReader::MAX_NESTING)
        fail("objects nested deeper than " + std::to_string(BoundedObjectReader::MAX_NESTING) + " levels");
    // A count read just before a '{' is the number of its entries (OSG writes "count {" for
    // arrays and lists), each at least a byte: a count beyond the room is a lie, and OSG would
    // resize an array to it before reading a byte of it (a 1.4 kB model made it allocate and
    // clear 2 GB, another reserve 11.7 GB; ModelFuzzer found them).
    if (count != kNoCount && count > room)
        fail(std::to_string(count) + " entries stated, with " + std::to_string(room) + " bytes for them");
    if (before == IdState::String) _idState = IdState::ObjectBrace;
}

void BoundedInputIterator::closeMark()
{
    if (_depth > 0) --_depth;
}

// --- BoundedBinaryIterator ----------------------------------------------------------------------

BoundedBinaryIterator::BoundedBinaryIterator(std::istream* in, bool byteSwap)
{
    _in = in;
    setByteSwap(byteSwap ? 1 : 0);
}

void BoundedBinaryIterator::readBool(bool& b)
{
    char c = 0;
    get(&c, 1, "a boolean");
    b = c != 0;
}

void BoundedBinaryIterator::readInt(int& i)
{
    const Expected expected = takeExpected();
    const IdState before = beginRead();
    const int step = _imageStep;
    number(&i, sizeof i, "an integer");
    afterInteger(before, expected, i < 0 ? 0 : static_cast<std::uint64_t>(i));
    _imageStep = step;
    imageSequence('i', i);
}

void BoundedBinaryIterator::readUInt(unsigned int& i)
{
    const bool afterArray = _afterArray;
    const bool levelsNext = _levelsNext;
    const Expected expected = takeExpected();
    const IdState before = beginRead();
    const int step = _imageStep;
    number(&i, sizeof i, "an integer");
    afterInteger(before, expected, i);
    if (_newImage)
        _imageStep = 1; // the image's own reads follow
    else
    {
        _imageStep = step;
        imageSequence('u', i);
    }
    if (levelsNext && std::uint64_t(i) * 4 > remaining())
        fail(std::to_string(i) + " mipmap levels stated for an image without data, with " +
             std::to_string(remaining()) + " bytes left in the data");
    // InputStream::readImage reads an image's data (readCharArray), then the number of its
    // mipmap levels, and value-initializes a vector of that many 4-byte offsets before it
    // reads one (a 1.4 kB model made it clear 16 GB; ModelFuzzer found it). Each offset is
    // 4 bytes of the file: more than the bytes left is a lie.
    if (afterArray && std::uint64_t(i) * 4 > remaining())
        fail(std::to_string(i) + " mipmap levels stated, with " + std::to_string(remaining()) +
             " bytes left in the data");
}

void BoundedBinaryIterator::readLong(long& l)
{
    std::int32_t v = 0; // 4 bytes in the file, whatever a long is here
    number(&v, sizeof v, "an integer");
    l = v;
}

void BoundedBinaryIterator::readULong(unsigned long& l)
{
    std::uint32_t v = 0;
    number(&v, sizeof v, "an integer");
    l = v;
}

void BoundedBinaryIterator::readString(std::string& s)
{
    const IdState before = beginRead();
    const int step = _imageStep;
    int size = 0;
    number(&size, sizeof size, "an integer");
    if (size < 0) fail("a string of negative length " + std::to_string(size));
    if (static_cast<std::uint64_t>(size) > remaining())
        fail("a string of " + std::to_string(size) + " bytes, with " + std::to_string(remaining()) +
             " left in the data");
    s.resize(static_cast<std::size_t>(size));
    if (size > 0) get(&s[0], static_cast<std::size_t>(size), "a string");
    afterString(before, s);
    _imageStep = step;
    imageSequence('s', 0);
}

void BoundedBinaryIterator::imageSequence(char kind, std::int64_t value)
{
    // InputStream::readImage (binary) after a new image's ID: the file name (a string), the
    // write hint and the decision (integers; 0 is data inline), the origin, size, formats,
    // packing and allocation mode (nine integers), the data's size (an unsigned integer), checked
    // against the bytes left. When that is 0 no data is read and the next integer is the mipmap
    // level count, which OSG makes a vector of before it reads one (a 2 kB model made it
    // allocate 13 GB; ModelFuzzer found it).
    const int step = _imageStep;
    _imageStep = 0;
    if (step == 0) return;
    const char expected = step == 1 ? 's' : step <= 12 ? 'i' : 'u';
    if (kind != expected) return;
    if (step == 3 && value != 0) return; // not inline data
    if (step == 13)
    {
        // The data's size: OSG allocates that many bytes before it reads one (4 GB stated by a
        // 2 kB model; under ASan the allocation alone took seconds; ModelFuzzer found it).
        if (static_cast<std::uint64_t>(value) > remaining())
            fail("an image of " + std::to_string(value) + " bytes stated, with " +
                 std::to_string(remaining()) + " bytes left in the data");
        _levelsNext = value == 0;
        return;
    }
    _imageStep = step + 1;
}

void BoundedBinaryIterator::readGLenum(osgDB::ObjectGLenum& value)
{
    std::uint32_t e = 0;
    number(&e, sizeof e, "a GL enum");
    value.set(e);
}

void BoundedBinaryIterator::readProperty(osgDB::ObjectProperty& prop)
{
    const IdState before = beginRead();
    int value = 0;
    if (prop._mapProperty) number(&value, sizeof value, "an enum");
    prop.set(value);
    afterProperty(before, prop._name);
}

void BoundedBinaryIterator::readMark(osgDB::ObjectMark& mark)
{
    const std::uint64_t count = _count;
    const IdState before = beginRead();
    if (mark._name == "}")
    {
        closeMark();
        if (_supportBinaryBrackets && !_blocks.empty()) _blocks.pop_back();
        return;
    }
    if (mark._name != "{") return;
    if (!_supportBinaryBrackets)
    {
        // Without block sizes (OSG's "robust" format off) the room is the rest of the data.
        openMark(before, count, remaining());
        return;
    }
    const std::uint64_t begin = position();
    std::uint64_t size = 0;
    if (getInputStream() && getInputStream()->getFileVersion() > 148)
        number(&size, sizeof size, "a block size");
    else
    {
        std::int32_t s32 = 0;
        number(&s32, sizeof s32, "a block size");
        if (s32 < 0) fail("a block of negative size");
        size = static_cast<std::uint64_t>(s32);
    }
    if (size > remaining() + (position() - begin))
        fail("a block of " + std::to_string(size) + " bytes, with " + std::to_string(remaining()) +
             " left in the data");
    openMark(before, count, size);
    _blocks.push_back({begin, size});
}

void BoundedBinaryIterator::readCharArray(char* s, unsigned int size)
{
    // OSG has allocated the array already (InputStream::readImage: new char[size], then this
    // read), and only takes ownership of it after this call: throwing here would leak it. So
    // the bytes there are read, the rest left as it is, and the next read throws, once OSG's
    // image owns the array and unwinding frees it. (Untouched, the array's pages cost no
    // memory.)
    const std::uint64_t left = remaining();
    if (size > left)
    {
        const std::string problem = at() + ": an array of " + std::to_string(size) + " bytes, with " +
                                    std::to_string(left) + " left in the data";
        if (left > 0) get(s, static_cast<std::size_t>(left), "an array");
        _truncated = problem;
        return;
    }
    if (size > 0) get(s, size, "an array");
    _afterArray = true;
}

void BoundedBinaryIterator::advanceToCurrentEndBracket()
{
    closeMark(); // an object's end (InputStream::readObject)
    if (!_supportBinaryBrackets || _blocks.empty()) return;
    const Block b = _blocks.back();
    _blocks.pop_back();
    _in->clear();
    _in->seekg(static_cast<std::streamoff>(b.begin + b.size));
    if (!*_in) throw MalformedFileError("a block ends past the end of the data");
}

std::uint64_t BoundedBinaryIterator::position()
{
    const std::streamoff p = _in->tellg();
    if (p < 0) throw MalformedFileError("the data ends early (a read failed)");
    return static_cast<std::uint64_t>(p);
}

std::uint64_t BoundedBinaryIterator::remaining()
{
    if (_sized != _in)
    {
        const std::streampos here = _in->tellg();
        _in->seekg(0, std::ios::end);
        _size = static_cast<std::uint64_t>(static_cast<std::streamoff>(_in->tellg()));
        _in->seekg(here);
        _sized = _in;
    }
    const std::uint64_t p = position();
    return p < _size ? _size - p : 0;
}

void BoundedBinaryIterator::get(void* p, std::size_t n, const char* what)
{
    beginRead(); // the reads of the ID and image sequences keep their state themselves
    _afterArray = false;
    _levelsNext = false;
    _imageStep = 0;
    if (!_truncated.empty()) throw MalformedFileError(_truncated);
    if (n > remaining()) fail(std::string("the data ends inside ") + what);
    _in->read(static_cast<char*>(p), static_cast<std::streamsize>(n));
    if (_in->gcount() != static_cast<std::streamsize>(n))
        throw MalformedFileError("the data ends inside " + std::string(what));
}

void BoundedBinaryIterator::number(void* p, std::size_t n, const char* what)
{
    get(p, n, what);
    if (_byteSwap) osg::swapBytes(static_cast<char*>(p), static_cast<unsigned int>(n));
}

// --- BoundedAsciiIterator -----------------------------------------------------------------------

BoundedAsciiIterator::BoundedAsciiIterator(std::istream* in, std::uint64_t size) : _size(size)
{
    _in = in;
}

std::uint64_t BoundedAsciiIterator::remaining()
{
    const std::streamoff p = _in->tellg();
    if (p < 0) return 0;
    return static_cast<std::uint64_t>(p) < _size ? _size - static_cast<std::uint64_t>(p) : 0;
}

std::string BoundedAsciiIterator::at()
{
    const std::streamoff p = _in->tellg();
    return p < 0 ? std::string("at the end of the text") : "byte " + std::to_string(p);
}

std::string BoundedAsciiIterator::word(const char* what)
{
    beginRead();
    _allocationMode = false;
    if (!_preRead.empty())
    {
        std::string w;
        std::swap(w, _preRead);
        return w;
    }
    std::string w;
    if (!(*_in >> w))
    {
        _in->clear();
        _in->seekg(0, std::ios::end);
        fail(std::string("the text ends where ") + what + " belongs");
    }
    return w;
}

long long BoundedAsciiIterator::integer(const char* what)
{
    const std::string w = word(what);
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(w.c_str(), &end, 0);
    if (end == w.c_str() || *end != '\0' || errno == ERANGE) fail("'" + w + "' where " + what + " belongs");
    return v;
}

int BoundedAsciiIterator::enumValue(const std::string& group, const std::string& name)
{
    // As ObjectWrapperManager::findLookup: the group's table, or the GL one.
    const osgDB::ObjectWrapperManager::IntLookupMap& groups =
        osgDB::Registry::instance()->getObjectWrapperManager()->getLookupMap();
    auto table = groups.find(group);
    if (table == groups.end()) table = groups.find("GL");
    if (table != groups.end())
    {
        const osgDB::IntLookup::StringToValue& known = table->second.getStringToValue();
        const auto found = known.find(name);
        if (found != known.end()) return found->second;
    }
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(name.c_str(), &end, 0);
    if (end == name.c_str() || *end != '\0' || errno == ERANGE)
        fail("'" + name + "' is not a value of " + group);
    return static_cast<int>(v);
}

void BoundedAsciiIterator::readBool(bool& b)
{
    const std::string w = word("a boolean");
    if (w == "TRUE")
        b = true;
    else if (w == "FALSE")
        b = false;
    else
        fail("'" + w + "' where TRUE or FALSE belongs");
}

void BoundedAsciiIterator::readChar(char& c)
{
    c = static_cast<char>(integer("a number"));
}

void BoundedAsciiIterator::readSChar(signed char& c)
{
    c = static_cast<signed char>(integer("a number"));
}

void BoundedAsciiIterator::readUChar(unsigned char& c)
{
    c = static_cast<unsigned char>(integer("a number"));
}

void BoundedAsciiIterator::readShort(short& s)
{
    s = static_cast<short>(integer("a number"));
}

void BoundedAsciiIterator::readUShort(unsigned short& s)
{
    s = static_cast<unsigned short>(integer("a number"));
}

void BoundedAsciiIterator::readInt(int& i)
{
    const bool allocationMode = _allocationMode;
    const Expected expected = takeExpected();
    const IdState before = beginRead();
    i = static_cast<int>(integer("an integer"));
    // InputStream::readImage decodes an inline image into new[] memory and hands it to the
    // image with the file's AllocationMode: anything but USE_NEW_DELETE frees it wrongly (free)
    // or never (ModelFuzzer found the mismatch).
    if (allocationMode) i = osg::Image::USE_NEW_DELETE;
    afterInteger(before, expected, i < 0 ? 0 : static_cast<std::uint64_t>(i));
}

void BoundedAsciiIterator::readUInt(unsigned int& i)
{
    const Expected expected = takeExpected();
    const IdState before = beginRead();
    i = static_cast<unsigned int>(integer("an integer"));
    afterInteger(before, expected, i);
}

void BoundedAsciiIterator::readLong(long& l)
{
    l = static_cast<long>(integer("an integer"));
}

void BoundedAsciiIterator::readULong(unsigned long& l)
{
    l = static_cast<unsigned long>(integer("an integer"));
}

void BoundedAsciiIterator::readFloat(float& f)
{
    double d = 0;
    readDouble(d);
    f = static_cast<float>(d);
}

void BoundedAsciiIterator::readDouble(double& d)
{
    const std::string w = word("a number");
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0') fail("'" + w + "' where a number belongs");
    if (!std::isfinite(v)) fail("'" + w + "' is not a finite number");
    d = osg::asciiToDouble(w.c_str()); // as OSG reads it
}

void BoundedAsciiIterator::readString(std::string& s)
{
    const IdState before = beginRead();
    s = word("a word");
    afterString(before, s);
}

void BoundedAsciiIterator::readGLenum(osgDB::ObjectGLenum& value)
{
    value.set(static_cast<GLenum>(enumValue("GL", word("a GL enum"))));
}

void BoundedAsciiIterator::readProperty(osgDB::ObjectProperty& prop)
{
    const IdState before = beginRead();
    const std::string w = word("a property name");
    int value = 0;
    if (prop._mapProperty)
        value = enumValue(prop._name, w);
    else if (w != prop._name)
        fail("'" + w + "' where '" + prop._name + "' belongs");
    prop.set(value);
    afterProperty(before, prop._name);
    _allocationMode = prop._name == "AllocationMode";
}

void BoundedAsciiIterator::readMark(osgDB::ObjectMark& mark)
{
    const std::uint64_t count = _count;
    const IdState before = beginRead();
    const std::string w = word(mark._name == "{" ? "'{'" : "'}'");
    if (w != mark._name) fail("'" + w + "' where '" + mark._name + "' belongs");
    if (mark._name == "{")
        openMark(before, count, remaining());
    else
        closeMark();
}

char BoundedAsciiIterator::character()
{
    if (!_preRead.empty())
    {
        const char c = _preRead[0];
        _preRead.erase(0, 1);
        return c;
    }
    const int c = _in->get();
    if (c == std::char_traits<char>::eof())
    {
        _in->clear();
        _in->seekg(0, std::ios::end);
        fail("the text ends inside a string");
    }
    return static_cast<char>(c);
}

void BoundedAsciiIterator::readWrappedString(std::string& s)
{
    beginRead();
    _allocationMode = false;
    char c = character();
    while (c == ' ' || c == '\n' || c == '\r')
        c = character();
    if (c == '"')
    {
        for (c = character(); c != '"'; c = character())
            s += c == '\\' ? character() : c;
        return;
    }
    // An unquoted string: to the first space or line end (or the end of the text).
    while (c != ' ' && c != '\0' && c != '\n')
    {
        s += c;
        if (_preRead.empty() && _in->peek() == std::char_traits<char>::eof()) return;
        c = character();
    }
}

bool BoundedAsciiIterator::matchString(const std::string& s)
{
    if (_preRead.empty())
    {
        beginRead();
        _allocationMode = false;
        if (!(*_in >> _preRead))
        {
            _preRead.clear();
            _in->clear();
            _in->seekg(0, std::ios::end);
            return false;
        }
    }
    if (_preRead != s) return false;
    _preRead.clear();
    return true;
}

void BoundedAsciiIterator::advanceToCurrentEndBracket()
{
    closeMark(); // an object's end (InputStream::readObject): its '}' is read here
    unsigned blocks = 0;
    for (;;)
    {
        const std::string w = word("an object's '}'");
        if (w == "}")
        {
            if (blocks == 0) return;
            --blocks;
        }
        else if (w == "{")
            ++blocks;
    }
}

} // namespace detail
} // namespace osgLoA
