/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/util/BoundedObjectReader>

#include <osgLoA/util/ModelValidation>

#include <osg/Endian>
#include <osg/Geometry>
#include <osgDB/FileNameUtils>
#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/ReaderWriter>
#include <osgDB/Registry>
#include <osgDB/Serializer>
#include <osgDB/StreamOperator>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include <sys/stat.h>

namespace osgLoA
{
namespace
{
// OSG's binary magic number (osgDB/Serializer's OSG_HEADER_LOW and _HIGH).
constexpr std::uint32_t kHeaderLow = 0x6C910EA1u;
constexpr std::uint32_t kHeaderHigh = 0x1AFB4545u;

std::uint32_t swapped(std::uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

[[noreturn]] void malformed(const std::string& what)
{
    throw MalformedFileError(what);
}

/** OSG's binary input iterator (osgdb_osg's BinaryInputIterator, same reads in the same order,
 *  byte swap and block brackets included) with every read checked: a size is compared with the
 *  bytes left before anything is allocated, and a read that comes back short throws. The
 *  stream may be replaced under it (InputStream::decompress hands it the inflated data), so the
 *  bytes left are measured on the stream of the moment. */
class BoundedBinaryIterator : public osgDB::InputIterator
{
public:
    BoundedBinaryIterator(std::istream* in, bool byteSwap)
    {
        _in = in;
        setByteSwap(byteSwap ? 1 : 0);
    }

    bool isBinary() const override { return true; }

    void readBool(bool& b) override
    {
        char c = 0;
        get(&c, 1, "a boolean");
        b = c != 0;
    }
    void readChar(char& c) override { get(&c, 1, "a character"); }
    void readSChar(signed char& c) override { get(&c, 1, "a character"); }
    void readUChar(unsigned char& c) override { get(&c, 1, "a character"); }
    void readShort(short& s) override { number(&s, sizeof s, "a short"); }
    void readUShort(unsigned short& s) override { number(&s, sizeof s, "a short"); }
    void readInt(int& i) override
    {
        number(&i, sizeof i, "an integer");
        _count = i < 0 ? 0 : static_cast<std::uint64_t>(i);
    }
    void readUInt(unsigned int& i) override
    {
        const bool afterArray = _afterArray;
        number(&i, sizeof i, "an integer");
        _count = i;
        // InputStream::readImage reads an image's data (readCharArray), then the number of its
        // mipmap levels, and value-initializes a vector of that many 4-byte offsets before it
        // reads one (a 1.4 kB model made it clear 16 GB; ModelFuzzer found it). Each offset is
        // 4 bytes of the file: more than the bytes left is a lie.
        if (afterArray && std::uint64_t(i) * 4 > remaining())
            malformed(at() + ": " + std::to_string(i) + " mipmap levels stated, with " +
                      std::to_string(remaining()) + " bytes left in the data");
    }
    void readLong(long& l) override
    {
        std::int32_t v = 0; // 4 bytes in the file, whatever a long is here
        number(&v, sizeof v, "an integer");
        l = v;
    }
    void readULong(unsigned long& l) override
    {
        std::uint32_t v = 0;
        number(&v, sizeof v, "an integer");
        l = v;
    }
    void readFloat(float& f) override { number(&f, sizeof f, "a number"); }
    void readDouble(double& d) override { number(&d, sizeof d, "a number"); }
    void readString(std::string& s) override
    {
        int size = 0;
        number(&size, sizeof size, "an integer");
        if (size < 0) malformed(at() + ": a string of negative length " + std::to_string(size));
        if (static_cast<std::uint64_t>(size) > remaining())
            malformed(at() + ": a string of " + std::to_string(size) + " bytes, with " +
                      std::to_string(remaining()) + " left in the data");
        s.resize(static_cast<std::size_t>(size));
        if (size > 0) get(&s[0], static_cast<std::size_t>(size), "a string");
    }
    void readStream(std::istream& (*)(std::istream&)) override {}
    void readBase(std::ios_base& (*)(std::ios_base&)) override {}
    void readGLenum(osgDB::ObjectGLenum& value) override
    {
        std::uint32_t e = 0;
        number(&e, sizeof e, "a GL enum");
        value.set(e);
    }
    void readProperty(osgDB::ObjectProperty& prop) override
    {
        int value = 0;
        if (prop._mapProperty) number(&value, sizeof value, "an enum");
        prop.set(value);
    }
    void readMark(osgDB::ObjectMark& mark) override
    {
        const std::uint64_t count = _count;
        _count = kNoCount;
        if (!_supportBinaryBrackets) return;
        if (mark._name == "{")
        {
            const std::uint64_t begin = position();
            std::uint64_t size = 0;
            if (getInputStream() && getInputStream()->getFileVersion() > 148)
                number(&size, sizeof size, "a block size");
            else
            {
                std::int32_t s32 = 0;
                number(&s32, sizeof s32, "a block size");
                if (s32 < 0) malformed(at() + ": a block of negative size");
                size = static_cast<std::uint64_t>(s32);
            }
            if (size > remaining() + (position() - begin))
                malformed(at() + ": a block of " + std::to_string(size) + " bytes, with " +
                          std::to_string(remaining()) + " left in the data");
            // A count read just before a block is the number of its entries (OSG writes
            // "count {" for arrays and lists), each at least a byte: a count beyond the block's
            // size is a lie, and OSG would resize an array to it before reading a byte of it (a
            // 1.4 kB model made it allocate and clear 2 GB; ModelFuzzer found it).
            if (count != kNoCount && count > size)
                malformed(at() + ": " + std::to_string(count) + " entries stated for a block of " +
                          std::to_string(size) + " bytes");
            _blocks.push_back({begin, size});
        }
        else if (mark._name == "}" && !_blocks.empty())
            _blocks.pop_back();
    }
    void readCharArray(char* s, unsigned int size) override
    {
        // OSG has allocated the array already (InputStream::readImage: new char[size], then this
        // read), and only takes ownership of it after this call: throwing here would leak it.
        // So the bytes there are read, the rest left as it is, and the next read throws, once
        // OSG's image owns the array and unwinding frees it. (Untouched, the array's pages
        // cost no memory.)
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
    void readWrappedString(std::string& s) override { readString(s); }
    void advanceToCurrentEndBracket() override
    {
        if (!_supportBinaryBrackets || _blocks.empty()) return;
        const Block b = _blocks.back();
        _blocks.pop_back();
        _in->clear();
        _in->seekg(static_cast<std::streamoff>(b.begin + b.size));
        if (!*_in) malformed(at() + ": a block ends past the end of the data");
    }

private:
    struct Block
    {
        std::uint64_t begin, size;
    };
    std::vector<Block> _blocks;
    std::string _truncated; ///< an array ran past the end: the next read fails with this
    static constexpr std::uint64_t kNoCount = ~std::uint64_t(0);
    std::uint64_t _count = kNoCount; ///< the integer of the last read, if it was readInt/readUInt
    bool _afterArray = false;        ///< the last read was readCharArray's
    const std::istream* _sized = nullptr;
    std::uint64_t _size = 0;

    std::uint64_t position()
    {
        const std::streamoff p = _in->tellg();
        if (p < 0) malformed("the data ends early (a read failed)");
        return static_cast<std::uint64_t>(p);
    }
    std::uint64_t remaining()
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
    std::string at() { return "byte " + std::to_string(position()); }
    void get(void* p, std::size_t n, const char* what)
    {
        _count = kNoCount; // only the read just before a block counts (readInt/readUInt set it after)
        _afterArray = false;
        if (!_truncated.empty()) malformed(_truncated);
        if (n > remaining()) malformed(at() + ": the data ends inside " + what);
        _in->read(static_cast<char*>(p), static_cast<std::streamsize>(n));
        if (_in->gcount() != static_cast<std::streamsize>(n))
            malformed("the data ends inside " + std::string(what));
    }
    void number(void* p, std::size_t n, const char* what)
    {
        get(p, n, what);
        if (_byteSwap) osg::swapBytes(static_cast<char*>(p), static_cast<unsigned int>(n));
    }
};

std::string streamError(osgDB::InputStream& is)
{
    const osgDB::InputException* e = is.getException();
    if (!e) return std::string();
    const std::string where = e->getField();
    return e->getError() + (where.empty() ? std::string() : " (at " + where + ")");
}

/** Runs an OSG read, mapping what escapes it to MalformedFileError: a failed read of the
 *  throwing text stream; std::bad_alloc for a size the data states; anything else OSG throws
 *  (its readers index with at() on counts the file states: an image of 0 levels made
 *  InputStream::readImage throw std::out_of_range, which ModelFuzzer found). */
template <class Read> auto guarded(const Read& read) -> decltype(read())
{
    try
    {
        return read();
    }
    catch (const std::ios_base::failure&)
    {
        malformed("the text ends before its objects do (a value or a list entry is missing, or a value does "
                  "not read as its type)");
    }
    catch (const MalformedFileError&)
    {
        throw;
    }
    catch (const std::bad_alloc&)
    {
        malformed("it states a size larger than this machine can hold");
    }
    catch (const std::exception& e)
    {
        malformed(std::string("OSG's reader failed on it (") + e.what() + ")");
    }
}

/** osg::Geometry's PrimitiveSetList as OSG 3.6.5 reads it (osgDB::VectorSerializer), except
 *  that an entry that did not read (an unknown class, "NULL") is left out: OSG's keeps it, and
 *  Geometry::setPrimitiveSetList then dereferences the null entry (SEGV in
 *  addElementBufferObjectIfRequired; ModelFuzzer found it). The reserve is capped: the count is
 *  the file's word. */
class PrimitiveSetListReader : public osgDB::VectorSerializer<osg::Geometry, osg::Geometry::PrimitiveSetList>
{
public:
    PrimitiveSetListReader()
        : VectorSerializer("PrimitiveSetList", &osg::Geometry::getPrimitiveSetList,
                           &osg::Geometry::getPrimitiveSetList, &osg::Geometry::setPrimitiveSetList,
                           osgDB::BaseSerializer::RW_OBJECT, 0)
    {
    }
    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        osg::Geometry& geometry = static_cast<osg::Geometry&>(obj);
        unsigned int size = 0;
        osg::Geometry::PrimitiveSetList list;
        const bool binary = is.isBinary();
        if (!binary && !is.matchString(_name)) return true;
        is >> size;
        list.reserve(std::min(size, 1u << 16));
        if (!binary && size > 0) is >> is.BEGIN_BRACKET;
        for (unsigned int i = 0; i < size; ++i)
        {
            osg::ref_ptr<osg::PrimitiveSet> value;
            is >> value;
            if (is.getException()) return false;
            if (value.valid()) list.push_back(value);
        }
        if (!binary && size > 0) is >> is.END_BRACKET;
        if (size > 0) geometry.setPrimitiveSetList(list);
        return true;
    }
};

/** Puts PrimitiveSetListReader in place of OSG's serializer, once per process (the wrapper is
 *  osgdb_serializers_osg's, loaded by the lookup). Every later read of osg::Geometry uses it. */
void guardGeometryWrapper()
{
    static std::once_flag once;
    std::call_once(once,
                   []
                   {
                       osgDB::ObjectWrapper* w =
                           osgDB::Registry::instance()->getObjectWrapperManager()->findWrapper(
                               "osg::Geometry");
                       if (!w) return;
                       for (osg::ref_ptr<osgDB::BaseSerializer>& serializer : w->getSerializerList())
                           if (serializer.valid() && serializer->getName() == "PrimitiveSetList")
                               serializer = new PrimitiveSetListReader;
                   });
}

osg::ref_ptr<osg::Object> readBinaryStream(osgDB::InputStream& is, osgDB::InputIterator& it, bool needNode);

osg::ref_ptr<osg::Object> readBinary(const std::string& data, const osgDB::Options* options, bool needNode)
{
    std::uint32_t low = 0, high = 0;
    std::memcpy(&low, data.data(), 4);
    std::memcpy(&high, data.data() + 4, 4);
    const bool swap = !(low == kHeaderLow && high == kHeaderHigh);
    // The content type word: OSG casts it to its ReadType enum unchecked (undefined behaviour
    // for a value outside it; ScenarioFileFuzzer found 16129).
    std::uint32_t type32 = 0;
    if (data.size() < 12) malformed("an OSG binary file cut short in its header");
    std::memcpy(&type32, data.data() + 8, 4);
    if (swap) type32 = swapped(type32);
    if (type32 > osgDB::InputStream::READ_OBJECT)
        malformed("an OSG binary file of unknown content type " + std::to_string(type32));
    std::istringstream in(data);
    in.seekg(8);
    osg::ref_ptr<BoundedBinaryIterator> it = new BoundedBinaryIterator(&in, swap);
    osgDB::InputStream is(options);
    return guarded([&] { return readBinaryStream(is, *it, needNode); });
}

osg::ref_ptr<osg::Object> readBinaryStream(osgDB::InputStream& is, osgDB::InputIterator& it, bool needNode)
{
    const osgDB::InputStream::ReadType type = is.start(&it);
    if (const std::string e = streamError(is); !e.empty()) malformed(e);
    if (type == osgDB::InputStream::READ_UNKNOWN) malformed("an OSG binary file of unknown content type");
    if (needNode && type != osgDB::InputStream::READ_SCENE && type != osgDB::InputStream::READ_OBJECT)
        malformed("an OSG binary file that holds no scene");
    is.decompress();
    if (const std::string e = streamError(is); !e.empty()) malformed(e);
    osg::ref_ptr<osg::Object> object = is.readObject();
    if (const std::string e = streamError(is); !e.empty()) malformed(e);
    return object;
}

osg::ref_ptr<osg::Object> readAscii(const std::string& data, const osgDB::Options* options, bool needNode)
{
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    if (!rw) malformed("no osgDB reader for OSG text files (osgdb_osg missing)");
    std::istringstream in(data);
    in.exceptions(std::ios::failbit | std::ios::badbit);
    osg::ref_ptr<osgDB::Options> local =
        options ? static_cast<osgDB::Options*>(options->clone(osg::CopyOp::SHALLOW_COPY))
                : new osgDB::Options;
    local->setPluginStringData("fileType", "Ascii");
    osgDB::ReaderWriter::ReadResult rr =
        guarded([&] { return needNode ? rw->readNode(in, local.get()) : rw->readObject(in, local.get()); });
    if (!rr.success() || !rr.getObject())
        malformed(rr.message().empty() ? std::string("OSG's text reader returned nothing") : rr.message());
    return rr.getObject();
}
} // namespace

BoundedObjectReader::Format BoundedObjectReader::formatOf(const std::string& data)
{
    if (data.size() >= 8)
    {
        std::uint32_t low = 0, high = 0;
        std::memcpy(&low, data.data(), 4);
        std::memcpy(&high, data.data() + 4, 4);
        if ((low == kHeaderLow && high == kHeaderHigh) ||
            (low == swapped(kHeaderLow) && high == swapped(kHeaderHigh)))
            return Format::Binary;
    }
    std::string firstWord;
    std::istringstream(data.substr(0, 64)) >> firstWord;
    if (firstWord == "#Ascii") return Format::Ascii;
    if (firstWord.compare(0, 5, "<?xml") == 0) return Format::Xml;
    return Format::Unknown;
}

osg::ref_ptr<osg::Object> BoundedObjectReader::readObject(const std::string& data,
                                                          const osgDB::Options* options)
{
    guardGeometryWrapper();
    switch (formatOf(data))
    {
    case Format::Binary:
        return readBinary(data, options, false);
    case Format::Ascii:
        return readAscii(data, options, false);
    case Format::Xml:
        malformed("OSG XML files are not read by the bounded reader");
    case Format::Unknown:
        break;
    }
    malformed("not an OSG file (neither the binary header nor '#Ascii')");
}

osg::ref_ptr<osg::Node> BoundedObjectReader::readNode(const std::string& data, const osgDB::Options* options)
{
    guardGeometryWrapper();
    osg::ref_ptr<osg::Object> o;
    switch (formatOf(data))
    {
    case Format::Binary:
        o = readBinary(data, options, true);
        break;
    case Format::Ascii:
        o = readAscii(data, options, true);
        break;
    case Format::Xml:
        malformed("OSG XML files are not read by the bounded reader");
    case Format::Unknown:
        malformed("not an OSG file (neither the binary header nor '#Ascii')");
    }
    osg::ref_ptr<osg::Node> node = dynamic_cast<osg::Node*>(o.get());
    if (!node)
        malformed(std::string("the file holds a ") + (o ? o->className() : "nothing") + ", not a scene");
    return node;
}

bool BoundedObjectReader::handlesExtension(const std::string& extension)
{
    return extension == "osgt" || extension == "osgb";
}

namespace
{
std::string fileData(const std::string& path)
{
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) malformed("cannot be opened: " + std::string(std::strerror(errno)));
    if (!S_ISREG(st.st_mode)) malformed("not a regular file (a device, FIFO or folder)");
    std::ifstream in(path.c_str(), std::ios::binary);
    if (!in) malformed("cannot be opened");
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) malformed("cannot be read");
    return bytes.str();
}

void checkStructure(const std::string& data)
{
    if (BoundedObjectReader::formatOf(data) != BoundedObjectReader::Format::Ascii) return;
    const std::string problem = ModelValidation::checkOsgtText(data);
    if (!problem.empty()) malformed("the OSG text file is incomplete: " + problem);
}

osg::ref_ptr<osgDB::Options> optionsFor(const std::string& path, const osgDB::Options* options)
{
    osg::ref_ptr<osgDB::Options> local =
        options ? static_cast<osgDB::Options*>(options->clone(osg::CopyOp::SHALLOW_COPY))
                : new osgDB::Options;
    local->getDatabasePathList().push_front(osgDB::getFilePath(path));
    return local;
}
} // namespace

osg::ref_ptr<osg::Object> BoundedObjectReader::readCheckedObject(const std::string& data,
                                                                 const osgDB::Options* options)
{
    checkStructure(data);
    return readObject(data, options);
}

osg::ref_ptr<osg::Node> BoundedObjectReader::readCheckedNode(const std::string& data,
                                                             const osgDB::Options* options)
{
    checkStructure(data);
    return readNode(data, options);
}

osg::ref_ptr<osg::Node> BoundedObjectReader::readNodeFile(const std::string& path,
                                                          const osgDB::Options* options)
{
    return readCheckedNode(fileData(path), optionsFor(path, options).get());
}

osg::ref_ptr<osg::Object> BoundedObjectReader::readObjectFile(const std::string& path,
                                                              const osgDB::Options* options)
{
    const std::string data = fileData(path);
    checkStructure(data);
    return readObject(data, optionsFor(path, options).get());
}

} // namespace osgLoA
