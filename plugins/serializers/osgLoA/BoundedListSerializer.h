// List, vector and object serializers that read malformed files without harm. OSG's
// ListSerializer and VectorSerializer trust the count in the file: "Configurations 4000000000 {"
// pushes one entry per count (a null one after the real ones end) for minutes, then runs out of
// memory. They also keep an object of any class (ListSerializer), or drop it silently
// (ObjectSerializer's readObjectOfType). These read
//  - a count only up to a limit (kMaxListObjects objects, kMaxListValues values), else the read
//    fails with "UsageScenario: Configurations count 4000000000 is above the limit of 65536";
//  - entries until the first failure (InputStream::getException), not on past it;
//  - objects of the element class only: "UsageScenario: Configurations entry 0: expected an
//    osgLoA::TransitionConfiguration, got osg::Node".
// Each is the OSG serializer with a checked read(): it writes what the OSG one writes, byte for
// byte, in .osgt, .osgx and .osgb (the committed library files stay as they are).
//
// Use them as ADD_LIST_SERIALIZER, ADD_VECTOR_SERIALIZER and ADD_OBJECT_SERIALIZER (inside
// REGISTER_OBJECT_WRAPPER); the list and object ones name the element class as well:
//     ADD_BOUNDED_LIST_SERIALIZER(Regions, osgLoA::UsageScenario::Regions, osgLoA::RegionOfInterest);
//     ADD_BOUNDED_VECTOR_SERIALIZER(Vertices, osgLoA::RegionOfInterest::Vertices,
//                                   osgDB::BaseSerializer::RW_VEC2D, 1);
//     ADD_CHECKED_OBJECT_SERIALIZER(Interest, osgLoA::FeatureInterest, NULL);
#ifndef OSGLOA_SERIALIZERS_BOUNDEDLISTSERIALIZER_H
#define OSGLOA_SERIALIZERS_BOUNDEDLISTSERIALIZER_H 1

#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

#include <stdexcept>
#include <string>

namespace osgLoA
{
/** The most objects a list in a scenario file may hold (real files hold a handful). */
constexpr unsigned kMaxListObjects = 1u << 16;
/** The most values (e.g. region vertices) a vector in a scenario file may hold. */
constexpr unsigned kMaxListValues = 1u << 20;

namespace serializer_detail
{
/** Reads "NAME COUNT" (text) or "COUNT" (binary) and checks the count against the limit. Returns
 *  false when the property is not in the text (nothing read) or the read failed (exception
 *  set, or already pending: an earlier error stands and nothing more is read). */
inline bool readCount(osgDB::InputStream& is, const std::string& label, const std::string& name,
                      unsigned limit, unsigned& size, bool& failed)
{
    failed = false;
    size = 0;
    if (is.getException()) return false;
    if (!is.isBinary() && !is.matchString(name)) return false;
    is >> size;
    if (!is.getException() && size > limit)
        is.throwException(label + ": " + name + " count " + std::to_string(size) + " is above the limit of " +
                          std::to_string(limit));
    failed = is.getException() != nullptr;
    return !failed;
}

/** Text formats only: after a failure inside "{ ... }", skips to the list's closing bracket so
 *  that the properties after it are not read from the middle of the list. */
inline bool failInsideBrackets(osgDB::InputStream& is)
{
    if (!is.isBinary()) is.advanceToCurrentEndBracket();
    return false;
}

/** The object's class as "osg::Node", or a note that there was none. */
inline std::string describeObject(const osg::Object* obj)
{
    if (!obj) return "no object (NULL or an unknown class)";
    return std::string(obj->libraryName()) + "::" + obj->className();
}
} // namespace serializer_detail

/** ListSerializer of osg::ref_ptr<T> (T an osg::Object) with a bounded, type-checked read. */
template <class C, class P> class BoundedListSerializer : public osgDB::ListSerializer<C, P>
{
public:
    typedef osgDB::ListSerializer<C, P> ParentType;
    typedef typename ParentType::ValueType ValueType;
    typedef typename ValueType::element_type ElementType;

    /** wrapperName: the wrapper's class ("osgLoA::UsageScenario"); elementName: ElementType's
     *  full name ("osgLoA::TransitionConfiguration"); both for messages. */
    BoundedListSerializer(const std::string& wrapperName, const char* name, const char* elementName,
                          typename ParentType::Getter gf, typename ParentType::Setter sf)
        : ParentType(name, gf, sf), _label(serializerClassLabel(wrapperName)), _elementName(elementName)
    {
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        C& object = OBJECT_CAST<C&>(obj);
        unsigned size = 0;
        bool failed = false;
        if (!serializer_detail::readCount(is, _label, this->_name, kMaxListObjects, size, failed))
            return !failed;
        if (size == 0) return true; // OSG writes no brackets (and no text at all) for an empty list
        const bool text = !is.isBinary();
        if (text) is >> is.BEGIN_BRACKET;
        if (is.getException()) return false;
        P list;
        for (unsigned i = 0; i < size; ++i)
        {
            osg::ref_ptr<osg::Object> entry = is.readObject();
            if (is.getException()) return serializer_detail::failInsideBrackets(is);
            ElementType* element = dynamic_cast<ElementType*>(entry.get());
            if (!element)
            {
                is.throwException(_label + ": " + this->_name + " entry " + std::to_string(i) +
                                  ": expected an " + _elementName + ", got " +
                                  serializer_detail::describeObject(entry.get()));
                return serializer_detail::failInsideBrackets(is);
            }
            list.push_back(element);
        }
        if (text) is >> is.END_BRACKET;
        if (is.getException()) return false;
        (object.*(this->_setter))(list);
        return true;
    }

private:
    std::string _label;
    std::string _elementName;
};

/** VectorSerializer (of plain values such as osg::Vec2d) with a bounded read. */
template <class C, class P> class BoundedVectorSerializer : public osgDB::VectorSerializer<C, P>
{
public:
    typedef osgDB::VectorSerializer<C, P> ParentType;
    typedef typename ParentType::ValueType ValueType;

    BoundedVectorSerializer(const std::string& wrapperName, const char* name,
                            typename ParentType::ConstGetter cgf, typename ParentType::Getter gf,
                            typename ParentType::Setter sf, osgDB::BaseSerializer::Type elementType,
                            unsigned numElementsOnRow)
        : ParentType(name, cgf, gf, sf, elementType, numElementsOnRow),
          _label(serializerClassLabel(wrapperName))
    {
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        C& object = OBJECT_CAST<C&>(obj);
        unsigned size = 0;
        bool failed = false;
        if (!serializer_detail::readCount(is, _label, this->_name, kMaxListValues, size, failed))
            return !failed;
        if (size == 0) return true;
        const bool text = !is.isBinary();
        if (text) is >> is.BEGIN_BRACKET;
        if (is.getException()) return false;
        P list;
        for (unsigned i = 0; i < size; ++i)
        {
            ValueType value;
            is >> value;
            if (is.getException()) return serializer_detail::failInsideBrackets(is);
            list.push_back(value);
        }
        if (text) is >> is.END_BRACKET;
        if (is.getException()) return false;
        (object.*(this->_setter))(list);
        return true;
    }

private:
    std::string _label;
};

/** ObjectSerializer whose read fails on an object of another class (OSG's sets null). */
template <class C, class P> class CheckedObjectSerializer : public osgDB::ObjectSerializer<C, P>
{
public:
    typedef osgDB::ObjectSerializer<C, P> ParentType;

    CheckedObjectSerializer(const std::string& wrapperName, const char* name, const char* elementName, P* def,
                            typename ParentType::Getter gf, typename ParentType::Setter sf)
        : ParentType(name, def, gf, sf), _label(serializerClassLabel(wrapperName)), _elementName(elementName)
    {
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        C& object = OBJECT_CAST<C&>(obj);
        if (is.getException()) return true; // an earlier property failed; that error stands
        const bool text = !is.isBinary();
        if (text && !is.matchString(this->_name)) return true;
        bool hasObject = false;
        is >> hasObject;
        if (is.getException()) return false;
        if (!hasObject) return true;
        if (text) is >> is.BEGIN_BRACKET;
        osg::ref_ptr<osg::Object> entry = is.readObject();
        if (is.getException()) return serializer_detail::failInsideBrackets(is);
        P* value = dynamic_cast<P*>(entry.get());
        if (!value)
        {
            is.throwException(_label + ": " + this->_name + ": expected an " + _elementName + ", got " +
                              serializer_detail::describeObject(entry.get()));
            return serializer_detail::failInsideBrackets(is);
        }
        if (text) is >> is.END_BRACKET;
        if (is.getException()) return false;
        (object.*(this->_setter))(value);
        return true;
    }

private:
    std::string _label;
    std::string _elementName;
};

/** CheckedObjectSerializer for a setter that refuses some values with std::invalid_argument (a
 *  node refusing a filter or a style): the read fails with the setter's message instead of the
 *  exception leaving osgDB. */
template <class C, class P> class RefusableObjectSerializer : public CheckedObjectSerializer<C, P>
{
public:
    using CheckedObjectSerializer<C, P>::CheckedObjectSerializer;
    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        try
        {
            return CheckedObjectSerializer<C, P>::read(is, obj);
        }
        catch (const std::invalid_argument& e)
        {
            is.throwException(e.what());
            return false;
        }
    }
};
} // namespace osgLoA

#define ADD_BOUNDED_LIST_SERIALIZER(PROP, TYPE, ELEMENT)                                                     \
    wrapper->addSerializer(new osgLoA::BoundedListSerializer<MyClass, TYPE>(wrapper->getName(), #PROP,       \
                                                                            #ELEMENT, &MyClass::get##PROP,   \
                                                                            &MyClass::set##PROP),            \
                           osgDB::BaseSerializer::RW_LIST)

#define ADD_BOUNDED_VECTOR_SERIALIZER(PROP, TYPE, ELEMENTTYPE, NUMELEMENTSONROW)                             \
    wrapper->addSerializer(new osgLoA::BoundedVectorSerializer<MyClass, TYPE>(                               \
                               wrapper->getName(), #PROP, &MyClass::get##PROP, &MyClass::get##PROP,          \
                               &MyClass::set##PROP, ELEMENTTYPE, NUMELEMENTSONROW),                          \
                           osgDB::BaseSerializer::RW_VECTOR)

#define ADD_CHECKED_OBJECT_SERIALIZER(PROP, TYPE, DEF)                                                       \
    wrapper->addSerializer(                                                                                  \
        new osgLoA::CheckedObjectSerializer<MyClass, TYPE>(wrapper->getName(), #PROP, #TYPE, DEF,            \
                                                           &MyClass::get##PROP, &MyClass::set##PROP),        \
        osgDB::BaseSerializer::RW_OBJECT)

#define ADD_REFUSABLE_OBJECT_SERIALIZER(PROP, TYPE, DEF)                                                     \
    wrapper->addSerializer(                                                                                  \
        new osgLoA::RefusableObjectSerializer<MyClass, TYPE>(wrapper->getName(), #PROP, #TYPE, DEF,          \
                                                             &MyClass::get##PROP, &MyClass::set##PROP),      \
        osgDB::BaseSerializer::RW_OBJECT)

namespace osgLoA
{
/** A list of strings written as OSG writes wrapped strings (count, brackets, one a line), for
 *  user serializers: reads at most `limit` entries (else fails naming `what`: "TransitionConfiguration:
 *  implausible sub-type count 70000"), stops at the first failed entry and returns false then
 *  (the caller sets nothing), and reads nothing after an earlier field's failure. */
inline bool readBoundedStrings(osgDB::InputStream& is, const std::string& what, unsigned limit,
                               std::vector<std::string>& out)
{
    if (is.getException()) return false; // an earlier field failed: keep its error
    const unsigned size = is.readSize();
    if (size > limit)
    {
        is.throwException(what + " count " + std::to_string(size));
        return false;
    }
    out.clear();
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
    {
        std::string s;
        is.readWrappedString(s);
        out.push_back(s);
    }
    is >> is.END_BRACKET;
    return !is.getException(); // a failed entry: no partial list is set
}

inline bool writeStrings(osgDB::OutputStream& os, const std::vector<std::string>& list)
{
    os.writeSize(list.size());
    os << os.BEGIN_BRACKET << std::endl;
    for (const std::string& s : list)
    {
        os.writeWrappedString(s);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}
} // namespace osgLoA

#endif
