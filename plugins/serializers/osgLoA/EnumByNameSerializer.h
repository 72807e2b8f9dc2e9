// An enum serializer that reads only the values it knows. OSG's EnumSerializer (and so
// BEGIN_ENUM_SERIALIZER) reads an unknown name as 0 and stores any number it finds ("Kind 7",
// "Interpolation 5") in the enum; this one fails the read with a message instead
// (InputStream::throwException: "SaliencyMetric: unknown Kind '7'").
//
// It writes what EnumSerializer writes, in every format (it is one, with a checked read()): in
// .osgt/.osgx the enumerator's name, nothing when the value is the default; in .osgb the int.
// Existing files therefore read and write byte for byte as before. Text files are read by name
// only (OSG writes a number only for a value it has no name for, which is an error here too);
// binary files by number, which must be one of the added values.
//
// Use it as BEGIN_ENUM_SERIALIZER, with OSG's ADD_ENUM_VALUE and END_ENUM_SERIALIZER:
//     BEGIN_ENUM_BY_NAME_SERIALIZER(Kind, VIEW_DISTANCE);
//         ADD_ENUM_VALUE(VIEW_DISTANCE);
//         ...
//     END_ENUM_SERIALIZER();
#ifndef OSGLOA_SERIALIZERS_ENUMBYNAMESERIALIZER_H
#define OSGLOA_SERIALIZERS_ENUMBYNAMESERIALIZER_H 1

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/Serializer>

#include <map>
#include <string>

namespace osgLoA
{
/** "osgLoA::SaliencyMetric" -> "SaliencyMetric": the class as the wrappers' messages name it. */
inline std::string serializerClassLabel(const std::string& wrapperName)
{
    const std::string::size_type colon = wrapperName.rfind("::");
    return colon == std::string::npos ? wrapperName : wrapperName.substr(colon + 2);
}

template <class C, class P> class EnumByNameSerializer : public osgDB::EnumSerializer<C, P, void>
{
public:
    typedef osgDB::EnumSerializer<C, P, void> ParentType;
    typedef typename ParentType::Getter Getter;
    typedef typename ParentType::Setter Setter;
    typedef osgDB::IntLookup::Value Value;

    /** wrapperName: the wrapper's class name ("osgLoA::SaliencyMetric"), for messages. */
    EnumByNameSerializer(const std::string& wrapperName, const char* name, P def, Getter gf, Setter sf)
        : ParentType(name, def, gf, sf), _label(serializerClassLabel(wrapperName))
    {
    }

    /** Hides EnumSerializer::add: also records the value as one that reads. (The parent's own
     *  lookup is not used for checking: its getValue and getString add every name or number
     *  they are asked about.) */
    void add(const char* str, P value)
    {
        ParentType::add(str, value);
        _byName[str] = static_cast<Value>(value);
        _byValue[static_cast<Value>(value)] = str;
    }

    bool read(osgDB::InputStream& is, osg::Object& obj) override
    {
        C& object = OBJECT_CAST<C&>(obj);
        if (is.getException()) return true; // an earlier property failed; that error stands
        Value value = 0;
        if (is.isBinary())
        {
            is >> value;
            if (is.getException()) return false;
            if (_byValue.find(value) == _byValue.end()) return fail(is, std::to_string(value));
        }
        else if (is.matchString(this->getName()))
        {
            std::string str;
            is >> str;
            if (is.getException()) return false;
            const auto found = _byName.find(str);
            if (found == _byName.end()) return fail(is, str);
            value = found->second;
        }
        else
        {
            return true; // not in the file: the default stays
        }
        (object.*(this->_setter))(static_cast<P>(value));
        return true;
    }

private:
    bool fail(osgDB::InputStream& is, const std::string& what)
    {
        is.throwException(_label + ": unknown " + this->getName() + " '" + what + "'");
        return false;
    }

    std::string _label;
    std::map<std::string, Value> _byName;
    std::map<Value, std::string> _byValue;
};
} // namespace osgLoA

/** As BEGIN_ENUM_SERIALIZER (inside REGISTER_OBJECT_WRAPPER); end with END_ENUM_SERIALIZER. */
#define BEGIN_ENUM_BY_NAME_SERIALIZER(PROP, DEF)                                                             \
    {                                                                                                        \
        typedef osgLoA::EnumByNameSerializer<MyClass, MyClass::PROP> MySerializer;                           \
        osg::ref_ptr<MySerializer> serializer = new MySerializer(wrapper->getName(), #PROP, MyClass::DEF,    \
                                                                 &MyClass::get##PROP, &MyClass::set##PROP)

#endif
