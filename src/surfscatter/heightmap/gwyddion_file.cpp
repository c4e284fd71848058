// The Gwyddion binding: the only file that includes Gwyddion and GLib headers (gwyddion_file.hpp).
#include "surfscatter/heightmap/gwyddion_file.hpp"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <app/settings.h>
#include <libgwyddion/gwyddion.h>
#include <libgwydgets/gwydgets.h>
#include <libgwymodule/gwymodule.h>
#include <libprocess/gwyprocess.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr double kMetreInUm = 1e6;

std::mutex& gwyddion_mutex() {
    static std::mutex mutex;
    return mutex;
}

// Gwyddion's modules link no library: they resolve libgwy*, GLib and GTK symbols in the process's global scope, where
// an executable linked with Gwyddion has them. A host that loaded this code with RTLD_LOCAL (Python loads extension
// modules so) keeps them out of it, and every module would fail to register; so the libraries this code was linked
// with (its DT_NEEDED entries, Gwyddion's among them) are promoted to the global scope, as in an executable.
void promote_linked_libraries() {
    Dl_info self;
    if (dladdr(reinterpret_cast<void*>(&promote_linked_libraries), &self) == 0 || self.dli_fname == nullptr) return;
    void* handle = dlopen(self.dli_fname, RTLD_NOW | RTLD_NOLOAD);
    if (handle == nullptr) return;  // the main program: its libraries are global already
    link_map* map = nullptr;
    std::vector<std::string> needed;
    if (dlinfo(handle, RTLD_DI_LINKMAP, &map) == 0 && map != nullptr) {
        const char* strings = nullptr;
        for (const ElfW(Dyn)* entry = map->l_ld; entry->d_tag != DT_NULL; ++entry)
            if (entry->d_tag == DT_STRTAB) strings = reinterpret_cast<const char*>(entry->d_un.d_ptr);
        for (const ElfW(Dyn)* entry = map->l_ld; strings != nullptr && entry->d_tag != DT_NULL; ++entry)
            if (entry->d_tag == DT_NEEDED) needed.emplace_back(strings + entry->d_un.d_val);
    }
    dlclose(handle);
    for (const std::string& name : needed) dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_GLOBAL);  // kept open
}

// Registers the file modules once per process (caller holds the mutex).
void initialise() {
    static bool done = false;
    if (done) return;
    promote_linked_libraries();
    gwy_widgets_type_init();
    gchar** dirs = gwy_app_settings_get_module_dirs();
    gwy_module_disable_registration("plugin-proxy");  // would run external plug-in programs
    gwy_module_register_modules(const_cast<const gchar**>(dirs));
    g_strfreev(dirs);
    done = true;
}

// GLib messages printed while a module runs, kept instead of written to stderr.
class CapturedMessages {
public:
    CapturedMessages() { previous_ = g_log_set_default_handler(&CapturedMessages::handle, &lines_); }
    ~CapturedMessages() { g_log_set_default_handler(previous_, nullptr); }
    CapturedMessages(const CapturedMessages&) = delete;
    CapturedMessages& operator=(const CapturedMessages&) = delete;
    std::vector<std::string> take() { return std::move(lines_); }

private:
    static void handle(const gchar* domain, GLogLevelFlags, const gchar* message, gpointer lines) {
        static_cast<std::vector<std::string>*>(lines)->push_back(
            fmt::format("Gwyddion{}{}: {}", domain ? " " : "", domain ? domain : "", message ? message : ""));
    }
    GLogFunc previous_;
    std::vector<std::string> lines_;
};

struct ObjectUnref {
    void operator()(gpointer object) const { g_object_unref(object); }
};
using ContainerPtr = std::unique_ptr<GwyContainer, ObjectUnref>;

std::string unit_string(GwySIUnit* unit) {
    gchar* text = gwy_si_unit_get_string(unit, GWY_SI_UNIT_FORMAT_PLAIN);
    std::string result = text && *text ? text : "no unit";
    g_free(text);
    return result;
}

// Image channel ids of a loaded container: keys "/<id>/data".
std::vector<int> channel_ids(GwyContainer* container) {
    std::vector<int> ids;
    gwy_container_foreach(
        container, nullptr,
        [](gpointer key, gpointer, gpointer out) {
            const char* name = g_quark_to_string(GPOINTER_TO_UINT(key));
            int id = -1, end = 0;
            if (std::sscanf(name, "/%d/data%n", &id, &end) == 1 && name[end] == '\0' && id >= 0)
                static_cast<std::vector<int>*>(out)->push_back(id);
        },
        &ids);
    std::sort(ids.begin(), ids.end());
    return ids;
}

std::string channel_title(GwyContainer* container, int id) {
    const guchar* title = nullptr;
    const std::string key = fmt::format("/{}/data/title", id);
    if (gwy_container_gis_string_by_name(container, key.c_str(), &title) && title)
        return reinterpret_cast<const char*>(title);
    return fmt::format("channel {}", id);
}

GwyDataField* field_at(GwyContainer* container, const std::string& key) {
    GObject* object = nullptr;
    if (!gwy_container_gis_object_by_name(container, key.c_str(), &object) || !GWY_IS_DATA_FIELD(object))
        return nullptr;
    return GWY_DATA_FIELD(object);
}

}  // namespace

std::string gwyddion_detect(const std::filesystem::path& path) {
    const std::lock_guard lock(gwyddion_mutex());
    initialise();
    CapturedMessages quiet;
    const gchar* name = gwy_file_detect(path.c_str(), FALSE, GWY_FILE_OPERATION_LOAD);
    return name ? name : "";
}

HeightMap gwyddion_read(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::lock_guard lock(gwyddion_mutex());
    initialise();
    CapturedMessages messages;
    const gchar* module = nullptr;
    GError* error = nullptr;
    ContainerPtr container(gwy_file_load_with_func(path.c_str(), GWY_RUN_NONINTERACTIVE, &module, &error));
    const std::string module_name = module ? module : "";
    if (!container) {
        const std::string message = error ? error->message : "no message";
        if (error) g_error_free(error);
        if (module_name.empty())
            fail("{}: unknown height map format: none of Gwyddion {}'s file modules recognises it ({})", path,
                 gwy_version_string(), message);
        fail("{}: Gwyddion's '{}' module ({}) cannot read it: {}", path, module_name,
             gwy_file_func_get_description(module_name.c_str()), message);
    }

    // The first channel with heights: lateral and z units metres (not V, deg, A, or unitless counts).
    const std::vector<int> ids = channel_ids(container.get());
    std::string others;
    for (int id : ids) {
        GwyDataField* field = field_at(container.get(), fmt::format("/{}/data", id));
        if (!field) continue;
        const std::string title = channel_title(container.get(), id);
        if (!gwy_si_unit_equal_string(gwy_data_field_get_si_unit_xy(field), "m") ||
            !gwy_si_unit_equal_string(gwy_data_field_get_si_unit_z(field), "m")) {
            others += fmt::format("{}'{}' (x, y in {}; z in {})", others.empty() ? "" : ", ", title,
                                  unit_string(gwy_data_field_get_si_unit_xy(field)),
                                  unit_string(gwy_data_field_get_si_unit_z(field)));
            continue;
        }
        const auto nx = static_cast<std::size_t>(gwy_data_field_get_xres(field));
        const auto ny = static_cast<std::size_t>(gwy_data_field_get_yres(field));
        const double* data = gwy_data_field_get_data_const(field);
        GwyDataField* mask = field_at(container.get(), fmt::format("/{}/mask", id));
        if (mask && (static_cast<std::size_t>(gwy_data_field_get_xres(mask)) != nx ||
                     static_cast<std::size_t>(gwy_data_field_get_yres(mask)) != ny))
            fail("{}: channel '{}' is {} x {} but its mask is {} x {} (inconsistent sizes)", path, title, nx, ny,
                 gwy_data_field_get_xres(mask), gwy_data_field_get_yres(mask));
        const double* masked = mask ? gwy_data_field_get_data_const(mask) : nullptr;
        std::vector<double> heights(nx * ny);
        std::vector<std::uint8_t> valid(nx * ny, 1);
        for (std::size_t i = 0; i < heights.size(); ++i) {
            heights[i] = data[i] * kMetreInUm;
            if ((masked && masked[i] > 0.5) || !std::isfinite(data[i])) valid[i] = 0;
        }
        const double dx = gwy_data_field_get_xreal(field) / static_cast<double>(nx) * kMetreInUm;
        const double dy = gwy_data_field_get_yreal(field) / static_cast<double>(ny) * kMetreInUm;
        HeightMap map(nx, ny, dx, dy, std::move(heights), std::move(valid), path);
        map.offset_x = gwy_data_field_get_xoffset(field) * kMetreInUm;
        map.offset_y = gwy_data_field_get_yoffset(field) * kMetreInUm;
        map.title = title;
        map.source.format = gwy_file_func_get_description(module_name.c_str());
        map.source.reader = fmt::format("gwyddion {}:{}", gwy_version_string(), module_name);
        if (ids.size() > 1) map.source.channel = fmt::format("{} '{}'", id, title);
        map.source.height_unit_um = kMetreInUm;
        map.source.warnings = messages.take();
        return map;
    }
    fail("{}: no height channel (x, y and z in metres) among the channels Gwyddion's '{}' module read: {}", path,
         module_name, others.empty() ? "none" : others);
}

void gwyddion_write_gwy(const HeightMap& map, const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::lock_guard lock(gwyddion_mutex());
    initialise();
    CapturedMessages messages;
    ContainerPtr container(gwy_container_new());
    GwyDataField* field = gwy_data_field_new(static_cast<gint>(map.nx()), static_cast<gint>(map.ny()),
                                             map.width() / kMetreInUm, map.height() / kMetreInUm, FALSE);
    gwy_si_unit_set_from_string(gwy_data_field_get_si_unit_xy(field), "m");
    gwy_si_unit_set_from_string(gwy_data_field_get_si_unit_z(field), "m");
    gwy_data_field_set_xoffset(field, map.offset_x / kMetreInUm);
    gwy_data_field_set_yoffset(field, map.offset_y / kMetreInUm);
    double* data = gwy_data_field_get_data(field);
    for (std::size_t i = 0; i < map.size(); ++i) data[i] = map.heights()[i] / kMetreInUm;
    gwy_container_set_object_by_name(container.get(), "/0/data", field);
    if (map.has_invalid()) {
        GwyDataField* mask = gwy_data_field_new_alike(field, TRUE);
        double* m = gwy_data_field_get_data(mask);
        for (std::size_t i = 0; i < map.size(); ++i) m[i] = map.valid(i) ? 0.0 : 1.0;
        gwy_container_set_object_by_name(container.get(), "/0/mask", mask);
        g_object_unref(mask);
    }
    g_object_unref(field);
    gwy_container_set_const_string_by_name(container.get(), "/0/data/title",
                                           reinterpret_cast<const guchar*>(map.title.empty() ? "Height" : map.title.c_str()));
    GError* error = nullptr;
    if (!gwy_file_func_run_save("gwyfile", container.get(), path.c_str(), GWY_RUN_NONINTERACTIVE, &error)) {
        const std::string message = error ? error->message : "no message";
        if (error) g_error_free(error);
        fail("{}: Gwyddion could not write the .gwy file: {}", path, message);
    }
}

std::string gwyddion_version() { return gwy_version_string(); }

std::size_t gwyddion_loader_count() {
    const std::lock_guard lock(gwyddion_mutex());
    initialise();
    std::size_t count = 0;
    gwy_file_func_foreach(
        [](gpointer name, gpointer counter) {
            if (gwy_file_func_get_operations(static_cast<const gchar*>(name)) & GWY_FILE_OPERATION_LOAD)
                ++*static_cast<std::size_t*>(counter);
        },
        &count);
    return count;
}

}  // namespace surfscatter::heightmap
