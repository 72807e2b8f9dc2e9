#include <osgLoA/semantics/ClassificationRule>

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace osgLoA
{

namespace
{
std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

enum CharClass
{
    SEPARATOR,
    LOWER,
    UPPER,
    DIGIT
};

CharClass classOf(unsigned char c)
{
    if (c >= 0x80 || std::islower(c)) return LOWER; // UTF-8 bytes belong to their word
    if (std::isupper(c)) return UPPER;
    if (std::isdigit(c)) return DIGIT;
    return SEPARATOR;
}

/** Splits at separators, lower-to-upper changes, "HTMLParser" -> HTML Parser, and between
 *  letters and digits; keeps the case. */
std::vector<std::string> splitTokens(const std::string& value)
{
    std::vector<std::string> out;
    std::string cur;
    for (std::size_t i = 0; i < value.size(); ++i)
    {
        const CharClass c = classOf(static_cast<unsigned char>(value[i]));
        if (c == SEPARATOR)
        {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
            continue;
        }
        if (!cur.empty())
        {
            const CharClass p = classOf(static_cast<unsigned char>(cur.back()));
            const bool letter = c != DIGIT, prevLetter = p != DIGIT;
            bool split = letter != prevLetter || (p == LOWER && c == UPPER);
            // "HTMLParser": the last capital before a lower-case letter starts a word.
            if (!split && p == UPPER && c == UPPER && i + 1 < value.size() &&
                classOf(static_cast<unsigned char>(value[i + 1])) == LOWER)
                split = true;
            if (split)
            {
                out.push_back(cur);
                cur.clear();
            }
        }
        cur += value[i];
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
}

bool endsWith(const std::string& s, const std::string& tail)
{
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/** A pattern word against one token: equal, a plural of it, or a prefix word ("build*"). */
bool wordMatches(const std::string& word, const std::string& token)
{
    if (word.back() == '*') return token.compare(0, word.size() - 1, word, 0, word.size() - 1) == 0;
    if (token == word) return true;
    if (token.size() == word.size() + 1 && endsWith(token, "s") && token.compare(0, word.size(), word) == 0)
        return true;
    if (token.size() == word.size() + 2 && endsWith(token, "es") && token.compare(0, word.size(), word) == 0)
        return true;
    return word.size() > 1 && endsWith(word, "y") && token.size() == word.size() + 2 &&
           endsWith(token, "ies") && token.compare(0, word.size() - 1, word, 0, word.size() - 1) == 0;
}
} // namespace

std::vector<std::string> ClassificationRule::tokenize(const std::string& value)
{
    std::vector<std::string> t = splitTokens(value);
    for (std::string& s : t)
        s = lower(s);
    return t;
}

ClassificationRule::ClassificationRule() {}

ClassificationRule::ClassificationRule(Field field, Syntax syntax, const std::string& pattern,
                                       FeatureType type, const std::string& subType)
    : _field(field), _syntax(syntax), _pattern(pattern), _type(type), _subType(subType)
{
}

ClassificationRule::ClassificationRule(const ClassificationRule& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _field(o._field), _userValueKey(o._userValueKey), _syntax(o._syntax),
      _pattern(o._pattern), _caseSensitive(o._caseSensitive), _type(o._type), _subType(o._subType),
      _inheritable(o._inheritable), _overridesModelData(o._overridesModelData)
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
    _alternatives.clear();
    _compileError.clear();
    if (_pattern.empty())
    {
        _compileError = "empty pattern";
        return;
    }
    if (_syntax == TOKENS)
    {
        std::size_t start = 0;
        for (;;)
        {
            const std::size_t bar = _pattern.find('|', start);
            const std::string alt = _pattern.substr(start, bar == std::string::npos ? bar : bar - start);
            std::vector<std::string> words;
            std::string word;
            auto flush = [&]
            {
                if (!word.empty()) words.push_back(_caseSensitive ? word : lower(word));
                word.clear();
            };
            for (char c : alt)
            {
                const unsigned char u = static_cast<unsigned char>(c);
                if (std::isalnum(u) || u >= 0x80)
                    word += c;
                else if (c == '*')
                {
                    if (word.empty())
                    {
                        _compileError = "'*' must end a word, as in 'build*'";
                        return;
                    }
                    word += c;
                    flush();
                }
                else if (c == ' ' || c == '-' || c == '_')
                    flush();
                else
                {
                    _compileError = std::string("character '") + c +
                                    "' in a token pattern (words, spaces, '|' and a final '*' only)";
                    return;
                }
            }
            flush();
            if (words.empty())
            {
                _compileError = "empty alternative in a token pattern";
                return;
            }
            _alternatives.push_back(words);
            if (bar == std::string::npos) break;
            start = bar + 1;
        }
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
    if (_syntax == TOKENS)
    {
        const std::vector<std::string> tokens = _caseSensitive ? splitTokens(value) : tokenize(value);
        for (const auto& words : _alternatives)
            for (std::size_t i = 0; i + words.size() <= tokens.size(); ++i)
            {
                bool all = true;
                for (std::size_t k = 0; k < words.size() && all; ++k)
                    all = wordMatches(words[k], tokens[i + k]);
                if (all) return true;
            }
        return false;
    }
    return fnmatch(_pattern.c_str(), value.c_str(), _caseSensitive ? 0 : FNM_CASEFOLD) == 0;
}

std::string ClassificationRule::describe() const
{
    std::string f = toString(_field);
    if (_field == USER_VALUE && !_userValueKey.empty()) f += "[" + _userValueKey + "]";
    std::string s = f + " " + toString(_syntax) + " '" + _pattern + "' -> " + osgLoA::toString(_type);
    if (!_subType.empty()) s += "/" + _subType;
    if (!_inheritable) s += " (not inherited)";
    if (_overridesModelData) s += " (overrides model data)";
    return s;
}

namespace
{
const char* const kFieldNames[] = {"name",    "description", "user-value", "material",
                                   "texture", "importer",    "any"};
}

const char* ClassificationRule::toString(Syntax s)
{
    switch (s)
    {
    case REGEX:
        return "regex";
    case TOKENS:
        return "tokens";
    default:
        return "glob";
    }
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
