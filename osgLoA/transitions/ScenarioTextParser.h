// Private to libosgLoA and its helper program loa-scenario-parse (not installed): the text
// scenario parse that ScenarioLibrary::readData runs out of process.
#ifndef OSGLOA_TRANSITIONS_SCENARIOTEXTPARSER_H
#define OSGLOA_TRANSITIONS_SCENARIOTEXTPARSER_H 1

#include <osgLoA/Export>

#include <string>

namespace osgLoA
{
namespace detail
{

/** Parses the bytes of a text scenario file (.osgt or .osgx) with osgDB's reader and returns
 *  the reply loa-scenario-parse sends back: "S" followed by the scenario in OSG's binary
 *  format, or "E" followed by a ScenarioError message naming label. Never throws; but OSG
 *  3.6.5's text readers can loop forever or crash on malformed text, so only the helper calls
 *  it (ScenarioLibrary::readData runs the helper with a deadline). */
OSGLOA_EXPORT std::string parseTextScenario(const std::string& text, const std::string& label);

} // namespace detail
} // namespace osgLoA

#endif
