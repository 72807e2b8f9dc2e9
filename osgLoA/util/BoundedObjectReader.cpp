/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/util/BoundedObjectReader>

#include <osgLoA/util/ModelValidation>

#include "BoundedInputIterator.h"

#include <osg/Endian>
#include <osg/Geometry>
#include <osg/Group>
#include <osgDB/FileNameUtils>
#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/ReaderWriter>
#include <osgDB/Registry>
#include <osgDB/Serializer>
#include <osgDB/StreamOperator>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <vector>

#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

namespace osgLoA
{
static_assert(BoundedObjectReader::MAX_NESTING == 2 * ModelValidation::MAX_SCENE_DEPTH + 256,
              "two '{' per scene level, and room for a leaf's contents");
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

using detail::BoundedAsciiIterator;
using detail::BoundedBinaryIterator;
using detail::BoundedInputIterator;

/** The read in progress on this thread: its InputStream and our iterator under it. */
struct CurrentRead
{
    const osgDB::InputStream* stream = nullptr;
    BoundedInputIterator* iterator = nullptr;
};
thread_local CurrentRead tCurrentRead;

/** A vector property (osgDB::VectorSerializer, IsAVectorSerializer: every osg::Array's data,
 *  DrawElements' indices) read as OSG reads it, after the count it states is checked: OSG reads
 *  the count and reserves room for it before it reads an entry, with no block around them in a
 *  binary file (a 1.4 kB model made it reserve 11.7 GB; ModelFuzzer found it). In a binary read
 *  of this reader, each entry takes at least min(its size, 4) bytes of the data (a number, a
 *  string's length, an object's class name). Everything else is the wrapped serializer's; in
 *  text, the count is checked before OSG parses (checkTextBounds), and reads by other readers
 *  (another InputStream) pass through unchanged. */
class BoundedVectorSerializer : public osgDB::VectorBaseSerializer
{
public:
    explicit BoundedVectorSerializer(osgDB::VectorBaseSerializer* wrapped)
        : VectorBaseSerializer(wrapped->getElementType(), wrapped->getElementSize()), _wrapped(wrapped)
    {
        setUsage(wrapped->getUsage());
        // The versions the wrapper reads the property in (protected in BaseSerializer; a
        // pointer to the member names it through this class).
        _firstVersion = wrapped->*(&BoundedVectorSerializer::_firstVersion);
        _lastVersion = wrapped->*(&BoundedVectorSerializer::_lastVersion);
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        BoundedInputIterator* it = tCurrentRead.stream == &is ? tCurrentRead.iterator : nullptr;
        if (!it) return _wrapped->read(is, obj);
        it->expectEntries(is.isBinary() ? std::min(std::max(getElementSize(), 1u), 4u) : 1u, getName());
        const bool ok = _wrapped->read(is, obj);
        it->clearExpected();
        return ok;
    }
    bool write(osgDB::OutputStream& os, const osg::Object& obj) override { return _wrapped->write(os, obj); }
    const std::string& getName() const override { return _wrapped->getName(); }
    bool set(osg::Object& obj, void* value) override { return _wrapped->set(obj, value); }
    bool get(const osg::Object& obj, void* value) override { return _wrapped->get(obj, value); }
    osgDB::IntLookup* getIntLookup() override { return _wrapped->getIntLookup(); }
    unsigned int size(const osg::Object& obj) const override { return _wrapped->size(obj); }
    void resize(osg::Object& obj, unsigned int n) const override { _wrapped->resize(obj, n); }
    void reserve(osg::Object& obj, unsigned int n) const override { _wrapped->reserve(obj, n); }
    void clear(osg::Object& obj) const override { _wrapped->clear(obj); }
    void addElement(osg::Object& obj, void* p) const override { _wrapped->addElement(obj, p); }
    void insertElement(osg::Object& obj, unsigned int i, void* p) const override
    {
        _wrapped->insertElement(obj, i, p);
    }
    void setElement(osg::Object& obj, unsigned int i, void* p) const override
    {
        _wrapped->setElement(obj, i, p);
    }
    void* getElement(osg::Object& obj, unsigned int i) const override { return _wrapped->getElement(obj, i); }
    const void* getElement(const osg::Object& obj, unsigned int i) const override
    {
        return static_cast<const osgDB::VectorBaseSerializer&>(*_wrapped).getElement(obj, i);
    }

private:
    osg::ref_ptr<osgDB::VectorBaseSerializer> _wrapped;
};

/** Puts our serializers in place of OSG's in every wrapper registered so far (the osg ones are
 *  loaded by the first lookup; those of other libraries when a file first names one of their
 *  classes, after which the next read covers them): PrimitiveSetListReader for osg::Geometry's
 *  PrimitiveSetList, BoundedVectorSerializer around every other vector property. Every later
 *  read, of any reader in the process, uses them; they read valid data as OSG's do. */
void guardWrappers()
{
    static std::mutex mutex;
    static std::size_t guarded = 0; // the number of wrappers seen last time
    const std::lock_guard<std::mutex> lock(mutex);
    osgDB::ObjectWrapperManager* manager = osgDB::Registry::instance()->getObjectWrapperManager();
    if (guarded == 0) manager->findWrapper("osg::Geometry"); // loads osgdb_serializers_osg
    osgDB::ObjectWrapperManager::WrapperMap& wrappers = manager->getWrapperMap();
    if (wrappers.size() == guarded) return;
    for (auto& entry : wrappers)
    {
        if (!entry.second.valid()) continue;
        for (osg::ref_ptr<osgDB::BaseSerializer>& serializer : entry.second->getSerializerList())
        {
            if (!serializer.valid() || dynamic_cast<BoundedVectorSerializer*>(serializer.get()) ||
                dynamic_cast<PrimitiveSetListReader*>(serializer.get()))
                continue;
            if (entry.first.compare(0, 8, "osgLoA::") == 0) continue; // ours check their own limits
            if (entry.first == "osg::Geometry" && serializer->getName() == "PrimitiveSetList")
                serializer = new PrimitiveSetListReader;
            else if (auto* vector = dynamic_cast<osgDB::VectorBaseSerializer*>(serializer.get()))
                serializer = new BoundedVectorSerializer(vector);
        }
    }
    guarded = wrappers.size();
}

/** A thread with a stack of BoundedObjectReader::STACK_BYTES (reserved, not committed) that runs
 *  one job at a time for the thread that owns it: one per calling thread, made on its first read
 *  and kept until that thread ends. A thread per read cost 0.14 ms of every model, scenario and
 *  rule set read (0.44 ms under ASan, which also clears the shadow of its stack). A read inside a
 *  read runs on the worker's own worker. A child process after fork() makes a new one (the
 *  parent's thread is not in it). */
class LargeStackWorker
{
public:
    static LargeStackWorker& forThisThread()
    {
        thread_local std::unique_ptr<LargeStackWorker> worker;
        if (worker && worker->_pid != ::getpid())
        {
            // Forked: the thread is not in this process; the object stays reachable, untouched.
            static std::vector<LargeStackWorker*> abandoned;
            abandoned.push_back(worker.release());
        }
        if (!worker) worker.reset(new LargeStackWorker);
        return *worker;
    }

    ~LargeStackWorker()
    {
        {
            std::lock_guard<std::mutex> lock(_mutex);
            _stop = true;
        }
        _wake.notify_one();
        pthread_join(_thread, nullptr);
    }

    /** Runs job (which must not throw) on the worker and returns when it is done. */
    void run(const std::function<void()>& job)
    {
        std::unique_lock<std::mutex> lock(_mutex);
        _job = &job;
        _done = false;
        _wake.notify_one();
        _finished.wait(lock, [this] { return _done; });
    }

private:
    LargeStackWorker() : _pid(::getpid())
    {
        pthread_attr_t attr;
        if (pthread_attr_init(&attr) != 0) throw std::runtime_error("cannot start the reading thread");
        pthread_attr_setstacksize(&attr, BoundedObjectReader::STACK_BYTES);
        const int started = pthread_create(&_thread, &attr, &LargeStackWorker::loop, this);
        pthread_attr_destroy(&attr);
        if (started != 0)
            throw std::runtime_error(std::string("cannot start the reading thread: ") +
                                     std::strerror(started));
    }

    static void* loop(void* self)
    {
        LargeStackWorker& w = *static_cast<LargeStackWorker*>(self);
        std::unique_lock<std::mutex> lock(w._mutex);
        for (;;)
        {
            w._wake.wait(lock, [&w] { return w._stop || w._job; });
            if (!w._job) return nullptr; // stopped
            const std::function<void()>* job = w._job;
            w._job = nullptr;
            lock.unlock();
            (*job)();
            lock.lock();
            w._done = true;
            w._finished.notify_one();
        }
    }

    const pid_t _pid;
    pthread_t _thread{};
    std::mutex _mutex;
    std::condition_variable _wake, _finished;
    const std::function<void()>* _job = nullptr;
    bool _done = false, _stop = false;
};

/** Runs read() on this thread's LargeStackWorker (OSG reads nested objects by recursion) and
 *  returns its result or rethrows what it threw. */
template <class Read> auto onLargeStack(const Read& read) -> decltype(read())
{
    decltype(read()) result{};
    std::exception_ptr error;
    LargeStackWorker::forThisThread().run(
        [&]
        {
            try
            {
                result = read();
            }
            catch (...)
            {
                error = std::current_exception();
            }
        });
    if (error) std::rethrow_exception(error);
    return result;
}

/** OSG's InputStream, which holds every object a read made by its UniqueID. When a read fails,
 *  the objects it made are freed with it, except those in a cycle: a group that names its own
 *  or an ancestor's ID among its children keeps itself alive (ModelFuzzer found the leak). So
 *  a failed read empties every group it made first. (A read that succeeds returns its graph,
 *  and ModelValidation cuts a cycle in it.) */
class BoundedInputStream : public osgDB::InputStream
{
public:
    using osgDB::InputStream::InputStream;
    ~BoundedInputStream() override
    {
        if (_failed)
            for (auto& entry : _identifierMap)
                if (osg::Group* group = dynamic_cast<osg::Group*>(entry.second.get()))
                    group->removeChildren(0, group->getNumChildren());
    }
    void markFailed() { _failed = true; }

private:
    bool _failed = false;
};

/** OSG's InputStream over one of our iterators, as osgdb_osg's ReaderWriterOSG2 runs it, on a
 *  thread with a large stack; the vector properties the read meets know its iterator. */
osg::ref_ptr<osg::Object> readStream(BoundedInputIterator& it, const osgDB::Options* options, bool needNode)
{
    return onLargeStack(
        [&]
        {
            BoundedInputStream is(options);
            struct Failure
            {
                BoundedInputStream& is;
                bool ok = false;
                ~Failure()
                {
                    if (!ok) is.markFailed();
                }
            } failure{is};
            tCurrentRead = {&is, &it};
            struct Reset
            {
                ~Reset() { tCurrentRead = CurrentRead(); }
            } reset;
            return guarded(
                [&]
                {
                    const char* const format = it.isBinary() ? "binary" : "text";
                    const osgDB::InputStream::ReadType type = is.start(&it);
                    if (const std::string e = streamError(is); !e.empty()) malformed(e);
                    if (type == osgDB::InputStream::READ_UNKNOWN)
                        malformed(std::string("an OSG ") + format + " file of unknown content type");
                    if (needNode && type != osgDB::InputStream::READ_SCENE &&
                        type != osgDB::InputStream::READ_OBJECT)
                        malformed(std::string("an OSG ") + format + " file that holds no scene");
                    is.decompress();
                    if (const std::string e = streamError(is); !e.empty()) malformed(e);
                    osg::ref_ptr<osg::Object> object = is.readObject();
                    if (const std::string e = streamError(is); !e.empty()) malformed(e);
                    failure.ok = true;
                    return object;
                });
        });
}

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
    return readStream(*it, options, needNode);
}

osg::ref_ptr<osg::Object> readAscii(const std::string& data, const osgDB::Options* options, bool needNode)
{
    std::istringstream in(data);
    std::string magic;
    in >> magic; // "#Ascii" (formatOf)
    osg::ref_ptr<BoundedAsciiIterator> it = new BoundedAsciiIterator(&in, data.size());
    osg::ref_ptr<osg::Object> object = readStream(*it, options, needNode);
    if (!object) malformed("OSG's text reader returned nothing");
    return object;
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
    guardWrappers();
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
    guardWrappers();
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
