/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#ifndef OSGLOA_UTIL_BOUNDEDINPUTITERATOR_H
#define OSGLOA_UTIL_BOUNDEDINPUTITERATOR_H 1

// Internal to BoundedObjectReader: the input iterators it puts under OSG's InputStream in place
// of osgdb_osg's (BinaryInputIterator, AsciiInputIterator), so that every value OSG's wrappers
// read is checked against the data before OSG acts on it.

#include <osgDB/StreamOperator>

#include <cstdint>
#include <istream>
#include <map>
#include <string>
#include <vector>

namespace osgLoA
{
namespace detail
{

/** The UniqueIDs a file gives its objects and images, by class. OSG's InputStream::readImage
 *  returns the object an ID already names cast to osg::Image unchecked (static_cast): a file
 *  that names a geometry's ID where an image belongs made OSG use the geometry as an image
 *  (memory corruption in Texture::setImage; ModelFuzzer found it). */
class SharedIds
{
public:
    /** An object of className read under id (the first class an ID is given is the one OSG keeps). */
    void object(std::uint64_t id, const std::string& className) { _classes.emplace(id, className); }
    /** An image read under id: "" or why the ID cannot stand for an image; isNew says whether
     *  the image is read here (else OSG reuses the one read before). */
    std::string image(std::uint64_t id, const std::string& className, bool& isNew);

private:
    std::map<std::uint64_t, std::string> _classes;
};

/** What both iterators check, whatever the encoding:
 *  - nesting: '{' within '{' at most BoundedObjectReader::MAX_NESTING deep (OSG reads nested
 *    objects by recursion). An object's '{' closes where OSG calls advanceToCurrentEndBracket,
 *    a list's at its '}';
 *  - counts: the integer read just before a '{' is the number of entries that follow ("count {"
 *    for lists and arrays), each at least a byte: no more than the room there is; and the count
 *    a vector property states (expectEntries);
 *  - IDs: OSG reads "UniqueID" in two places only, right after an object's class name and '{'
 *    (InputStream::readObject, whose callers check the class) and after an image's "ClassName"
 *    (readImage, which does not): SharedIds. */
class BoundedInputIterator : public osgDB::InputIterator
{
public:
    /** The next integer read is the number of entries of the vector property `name`, each at
     *  least entryBytes bytes of the data (BoundedVectorSerializer says so before OSG's
     *  serializer reads it). */
    void expectEntries(unsigned entryBytes, const std::string& name) { _expected = {entryBytes, name}; }
    void clearExpected() { _expected = Expected(); }

protected:
    /** Bytes of the data after the read position. */
    virtual std::uint64_t remaining() = 0;
    /** "byte N", where the read position is. */
    virtual std::string at() = 0;
    /** Throws MalformedFileError "at(): what". */
    [[noreturn]] void fail(const std::string& what);

    /** Where the reads stand in OSG's two ways of reading a UniqueID: class name, '{',
     *  "UniqueID", id (an object); "ClassName", class name, "UniqueID", id (an image). */
    enum class IdState
    {
        None,
        String,            ///< a string was read (a class name, if '{' follows)
        ObjectBrace,       ///< a string and '{'
        ObjectId,          ///< ... and the UniqueID property: the next integer is an object's ID
        ClassNameProperty, ///< the ClassName property: an image's class name follows
        ImageClass,        ///< ... and it was read
        ImageId            ///< the UniqueID property elsewhere: the next integer is an image's ID
    };
    struct Expected
    {
        unsigned entryBytes = 0; ///< 0: nothing expected
        std::string name;
    };
    static constexpr std::uint64_t kNoCount = ~std::uint64_t(0);

    /** Every read starts here: the sequence state before it, then reset. */
    IdState beginRead();
    Expected takeExpected();
    void afterString(IdState before, const std::string& s);
    void afterProperty(IdState before, const std::string& name);
    /** An integer read: checks what was expected of it; an ID is checked or recorded. */
    void afterInteger(IdState before, const Expected& expected, std::uint64_t value);
    /** A '{': nesting, and the count read just before it against `room` bytes. */
    void openMark(IdState before, std::uint64_t count, std::uint64_t room);
    void closeMark();

    std::uint64_t _count = kNoCount; ///< the value of the last read, if it was an integer
    bool _newImage = false;          ///< the last read was the ID of an image read from here on

private:
    Expected _expected;
    unsigned _depth = 0;
    IdState _idState = IdState::None;
    std::string _className; ///< the class the next ID belongs to
    SharedIds _ids;
};

/** OSG's binary encoding (osgdb_osg's BinaryInputIterator: the same reads in the same order,
 *  byte swap and block brackets included) with every read checked: a size is compared with the
 *  bytes left before anything is allocated, and a read that comes back short throws. The
 *  stream may be replaced under it (InputStream::decompress hands it the inflated data), so the
 *  bytes left are measured on the stream of the moment. */
class BoundedBinaryIterator : public BoundedInputIterator
{
public:
    BoundedBinaryIterator(std::istream* in, bool byteSwap);

    bool isBinary() const override { return true; }
    void readBool(bool& b) override;
    void readChar(char& c) override { get(&c, 1, "a character"); }
    void readSChar(signed char& c) override { get(&c, 1, "a character"); }
    void readUChar(unsigned char& c) override { get(&c, 1, "a character"); }
    void readShort(short& s) override { number(&s, sizeof s, "a short"); }
    void readUShort(unsigned short& s) override { number(&s, sizeof s, "a short"); }
    void readInt(int& i) override;
    void readUInt(unsigned int& i) override;
    void readLong(long& l) override;
    void readULong(unsigned long& l) override;
    void readFloat(float& f) override { number(&f, sizeof f, "a number"); }
    void readDouble(double& d) override { number(&d, sizeof d, "a number"); }
    void readString(std::string& s) override;
    void readStream(std::istream& (*)(std::istream&)) override {}
    void readBase(std::ios_base& (*)(std::ios_base&)) override {}
    void readGLenum(osgDB::ObjectGLenum& value) override;
    void readProperty(osgDB::ObjectProperty& prop) override;
    void readMark(osgDB::ObjectMark& mark) override;
    void readCharArray(char* s, unsigned int size) override;
    void readWrappedString(std::string& s) override { readString(s); }
    void advanceToCurrentEndBracket() override;

protected:
    std::uint64_t remaining() override;
    std::string at() override { return "byte " + std::to_string(position()); }

private:
    struct Block
    {
        std::uint64_t begin, size;
    };
    std::vector<Block> _blocks;
    std::string _truncated;   ///< an array ran past the end: the next read fails with this
    bool _afterArray = false; ///< the last read was readCharArray's
    /** Reads since a new image's ID in InputStream::readImage (file name, write hint, decision,
     *  nine numbers, the data's size), 0 when not in one; _levelsNext: the size was 0, so the
     *  next integer is the image's mipmap level count. */
    int _imageStep = 0;
    bool _levelsNext = false;
    void imageSequence(char kind, std::int64_t value);
    const std::istream* _sized = nullptr;
    std::uint64_t _size = 0;

    std::uint64_t position();
    void get(void* p, std::size_t n, const char* what);
    void number(void* p, std::size_t n, const char* what);
};

/** OSG's text encoding (osgdb_osg's AsciiInputIterator: words separated by white space, the
 *  same pre-read word for matchString, the same quoted strings) read strictly: a number must
 *  be a whole number word, TRUE or FALSE a boolean, an enum name one OSG knows (OSG's lookup
 *  adds every unknown name to a global table), a property the name OSG expects there, a mark
 *  '{' or '}' itself; the end of the text where a value belongs is an error. OSG's reader takes
 *  any word for any of these (a bad number reads as 0), so a mutated file read as a different
 *  structure; its loop on a failed stream (a text cut short) does not arise. An inline image's
 *  AllocationMode is read as USE_NEW_DELETE whatever the file says: OSG's reader allocates the
 *  decoded data with new[] and would free it as the file says. */
class BoundedAsciiIterator : public BoundedInputIterator
{
public:
    /** `in` positioned after the "#Ascii" word, holding `size` bytes in all. */
    BoundedAsciiIterator(std::istream* in, std::uint64_t size);

    bool isBinary() const override { return false; }
    void readBool(bool& b) override;
    void readChar(char& c) override;
    void readSChar(signed char& c) override;
    void readUChar(unsigned char& c) override;
    void readShort(short& s) override;
    void readUShort(unsigned short& s) override;
    void readInt(int& i) override;
    void readUInt(unsigned int& i) override;
    void readLong(long& l) override;
    void readULong(unsigned long& l) override;
    void readFloat(float& f) override;
    void readDouble(double& d) override;
    void readString(std::string& s) override;
    void readStream(std::istream& (*)(std::istream&)) override {}
    void readBase(std::ios_base& (*)(std::ios_base&)) override {}
    void readGLenum(osgDB::ObjectGLenum& value) override;
    void readProperty(osgDB::ObjectProperty& prop) override;
    void readMark(osgDB::ObjectMark& mark) override;
    void readCharArray(char*, unsigned int) override {}
    void readWrappedString(std::string& s) override;
    bool matchString(const std::string& s) override;
    void advanceToCurrentEndBracket() override;

protected:
    std::uint64_t remaining() override;
    std::string at() override;

private:
    std::string _preRead; ///< a word matchString read and did not match
    std::uint64_t _size;
    bool _allocationMode = false; ///< the last property was AllocationMode

    /** The next word (the pre-read one first); `what` names the value for the error at the end. */
    std::string word(const char* what);
    /** The next word as an integer as OSG reads it (strtol/strtoul, base 0), the whole word. */
    long long integer(const char* what);
    /** A value of an enum group: a name OSG's lookup knows, or a number. */
    int enumValue(const std::string& group, const std::string& name);
    char character();
};

} // namespace detail
} // namespace osgLoA

#endif
