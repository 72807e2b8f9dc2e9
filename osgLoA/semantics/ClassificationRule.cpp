#include <osgLoA/semantics/ClassificationRule>

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace osgLoA
{

ClassificationRule::ClassificationRule() {}

ClassificationRule::ClassificationRule(Field field, Syntax syntax, const std::string& pattern,
                                       FeatureType type, const std::string& subType)
    : _field(field), _syntax(syntax), _pattern(pattern), _type(type), _subType(subType)
{
}

ClassificationRule::ClassificationRule(const ClassificationRule& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _field(o._field), _userValueKey(o._userValueKey), _syntax(o._syntax),
      _pattern(o._pattern), _caseSensitive(o._caseSensitive), _type(o._type), _subType(o._subType)
{
}

void ClassificationRule::setSyntax(Syntax s)
{
    _syntax = s;
    _compiled = false;
}

void ClassificationRule::setPattern(const std::string& p)
{
    _pattern = p;
    _compiled = false;
}

void ClassificationRule::setCaseSensitive(bool b)
{
    _caseSensitive = b;
    _compiled = false;
}

void ClassificationRule::compile() const
{
    _compiled = true;
    _regex.reset();
    _compileError.clear();
    if (_pattern.empty())
    {
        _compileError = "empty pattern";
        return;
    }
    if (_syntax != REGEX) return;
    try
    {
        auto flags = std::regex::ECMAScript | std::regex::optimize;
        if (!_caseSensitive) flags |= std::regex::icase;
        _regex = std::make_shared<std::regex>(_pattern, flags);
    }
    catch (const std::regex_error& e)
    {
        _compileError = std::string("regular expression does not compile: ") + e.what();
    }
}

void ClassificationRule::validate() const
{
    if (!_compiled) compile();
    if (!_compileError.empty())
        throw std::invalid_argument("classification rule " + describe() + ": " + _compileError);
}

bool ClassificationRule::matches(const std::string& value) const
{
    if (!_compiled) compile();
    if (!_compileError.empty()) return false;
    if (_syntax == REGEX) return std::regex_search(value, *_regex);
    return fnmatch(_pattern.c_str(), value.c_str(), _caseSensitive ? 0 : FNM_CASEFOLD) == 0;
}

std::string ClassificationRule::describe() const
{
    std::string f = toString(_field);
    if (_field == USER_VALUE && !_userValueKey.empty()) f += "[" + _userValueKey + "]";
    std::string s =
        f + (_syntax == REGEX ? " regex '" : " glob '") + _pattern + "' -> " + osgLoA::toString(_type);
    if (!_subType.empty()) s += "/" + _subType;
    return s;
}

namespace
{
const char* const kFieldNames[] = {"name",    "description", "user-value", "material",
                                   "texture", "importer",    "any"};
}

const char* ClassificationRule::toString(Field f)
{
    const int i = static_cast<int>(f);
    return i >= 0 && i <= static_cast<int>(ANY) ? kFieldNames[i] : "any";
}

bool ClassificationRule::parseField(const std::string& name, Field& f)
{
    std::string n = name;
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::tolower(c); });
    for (int i = 0; i <= static_cast<int>(ANY); ++i)
        if (n == kFieldNames[i])
        {
            f = static_cast<Field>(i);
            return true;
        }
    return false;
}

} // namespace osgLoA
