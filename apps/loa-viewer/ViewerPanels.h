// loa-viewer's ImGui panels: tools, scenario library, configuration editor, style editor,
// feature inspector. They read and edit through ViewerSession (every edit undoable).
#ifndef OSGLOA_APPS_VIEWERPANELS_H
#define OSGLOA_APPS_VIEWERPANELS_H 1

#include "ViewerSession.h"

#include <osgViewer/View>

namespace loa
{

class ViewerPanels
{
public:
    ViewerPanels(ViewerSession& session, osgViewer::View& view) : _session(&session), _view(&view) {}
    /** Builds every panel (between ImGui::NewFrame and ImGui::Render). */
    void build();
    /** The configuration the editors show. */
    unsigned selected = 0;

private:
    void tools();
    void library();
    void configuration();
    void style();
    void feature();

    ViewerSession* _session;
    osgViewer::View* _view;
    char _saveAs[512] = {0};
    char _duplicateName[128] = {0};
    char _subTypes[256] = {0};
    unsigned _subTypesFor = ~0u;
    unsigned _libraryChoice = 0;
    int _typeChoice = 0;
};

} // namespace loa

#endif
