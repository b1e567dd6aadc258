/* SPDX-License-Identifier: MIT */
/* ocio_shim.cpp: the extern "C" wrapper over OpenColorIO (docs/design.md §6).
 * No exception crosses the C boundary: every entry point catches them all. */
#include "ocio_shim.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include <OpenColorIO/OpenColorIO.h>

namespace OCIO = OCIO_NAMESPACE;

struct ocio_config {
	OCIO::ConstConfigRcPtr cfg; /* the loaded config */
};

struct ocio_proc {
	OCIO::ConstCPUProcessorRcPtr cpu; /* default-optimised CPU processor */
};

/* Copies msg into err (truncating), when there is room for it. */
static void set_err(char *err, size_t errlen, const char *msg)
{
	if (err && errlen)
		std::snprintf(err, errlen, "%s", msg ? msg : "unknown OpenColorIO error");
}

/* CreateFromFile (never CreateFromEnv: with $OCIO unset it returns a raw config
 * and prints to stderr), then validate(). */
extern "C" struct ocio_config *ocio_config_load(const char *path, char *err, size_t errlen)
{
	try {
		OCIO::ConstConfigRcPtr c;
		if (path && *path) {
			c = OCIO::Config::CreateFromFile(path);
		} else {
			const char *env = std::getenv("OCIO");
			if (!env || !*env) {
				set_err(err, errlen, "no OCIO config: $OCIO is not set");
				return nullptr;
			}
			c = OCIO::Config::CreateFromFile(env);
		}
		c->validate();
		ocio_config *r = new ocio_config;
		r->cfg = c;
		return r;
	} catch (const std::exception &e) {
		set_err(err, errlen, e.what());
	} catch (...) {
		set_err(err, errlen, nullptr);
	}
	return nullptr;
}

extern "C" void ocio_config_free(struct ocio_config *cfg) { delete cfg; }

extern "C" int ocio_display_count(const struct ocio_config *cfg)
{
	try {
		return cfg->cfg->getNumDisplays();
	} catch (...) {
		return 0;
	}
}

extern "C" const char *ocio_display_name(const struct ocio_config *cfg, int i)
{
	try {
		if (i < 0 || i >= cfg->cfg->getNumDisplays())
			return nullptr;
		return cfg->cfg->getDisplay(i);
	} catch (...) {
		return nullptr;
	}
}

extern "C" const char *ocio_default_display(const struct ocio_config *cfg)
{
	try {
		return cfg->cfg->getDefaultDisplay();
	} catch (...) {
		return nullptr;
	}
}

/* True when display is one of the config's active displays. */
static bool has_display(const OCIO::ConstConfigRcPtr &c, const char *display)
{
	if (!display)
		return false;
	for (int i = 0; i < c->getNumDisplays(); i++)
		if (std::string(c->getDisplay(i)) == display)
			return true;
	return false;
}

extern "C" int ocio_view_count(const struct ocio_config *cfg, const char *display)
{
	try {
		return has_display(cfg->cfg, display) ? cfg->cfg->getNumViews(display) : 0;
	} catch (...) {
		return 0;
	}
}

extern "C" const char *ocio_view_name(const struct ocio_config *cfg, const char *display,
                                      int i)
{
	try {
		if (!has_display(cfg->cfg, display) || i < 0 || i >= cfg->cfg->getNumViews(display))
			return nullptr;
		return cfg->cfg->getView(display, i);
	} catch (...) {
		return nullptr;
	}
}

extern "C" const char *ocio_default_view(const struct ocio_config *cfg, const char *display)
{
	try {
		return has_display(cfg->cfg, display) ? cfg->cfg->getDefaultView(display) : nullptr;
	} catch (...) {
		return nullptr;
	}
}

extern "C" int ocio_has_colorspace(const struct ocio_config *cfg, const char *name)
{
	try {
		return name && cfg->cfg->getColorSpace(name) ? 1 : 0;
	} catch (...) {
		return 0;
	}
}

/* One line per display: "Display": "View", ... (for --help and errors). */
extern "C" size_t ocio_describe_views(const struct ocio_config *cfg, char *buf, size_t len)
{
	try {
		std::string s;
		for (int d = 0; d < cfg->cfg->getNumDisplays(); d++) {
			const char *disp = cfg->cfg->getDisplay(d);
			s += std::string("\"") + disp + "\":";
			for (int v = 0; v < cfg->cfg->getNumViews(disp); v++)
				s += std::string(v ? ", \"" : " \"") + cfg->cfg->getView(disp, v) + "\"";
			s += "\n";
		}
		if (buf && len)
			std::snprintf(buf, len, "%s", s.c_str());
		return s.size();
	} catch (...) {
		if (buf && len)
			buf[0] = '\0';
		return 0;
	}
}

/* Wraps a processor's default CPU processor into a new ocio_proc. */
static ocio_proc *wrap(const OCIO::ConstProcessorRcPtr &p)
{
	ocio_proc *r = new ocio_proc;
	r->cpu = p->getDefaultCPUProcessor();
	return r;
}

/* src (default scene_linear role) → display/view, forward direction. */
extern "C" struct ocio_proc *ocio_proc_display(const struct ocio_config *cfg, const char *src,
                                               const char *display, const char *view,
                                               char *err, size_t errlen)
{
	try {
		if (!src || !*src)
			src = OCIO::ROLE_SCENE_LINEAR;
		return wrap(cfg->cfg->getProcessor(src, display ? display : "", view ? view : "",
		                                   OCIO::TRANSFORM_DIR_FORWARD));
	} catch (const std::exception &e) {
		set_err(err, errlen, e.what());
	} catch (...) {
		set_err(err, errlen, nullptr);
	}
	return nullptr;
}

/* Colour space (or role) to colour space, e.g. texture decoding. */
extern "C" struct ocio_proc *ocio_proc_convert(const struct ocio_config *cfg, const char *src,
                                               const char *dst, char *err, size_t errlen)
{
	try {
		return wrap(cfg->cfg->getProcessor(src ? src : "", dst ? dst : ""));
	} catch (const std::exception &e) {
		set_err(err, errlen, e.what());
	} catch (...) {
		set_err(err, errlen, nullptr);
	}
	return nullptr;
}

/* In place on npix packed RGB triples, as one npix x 1 image. */
extern "C" int ocio_proc_apply_rgb(const struct ocio_proc *p, float *rgb, long npix, char *err,
                                   size_t errlen)
{
	try {
		if (npix <= 0)
			return 0;
		OCIO::PackedImageDesc img(rgb, npix, 1, 3);
		p->cpu->apply(img);
		return 0;
	} catch (const std::exception &e) {
		set_err(err, errlen, e.what());
	} catch (...) {
		set_err(err, errlen, nullptr);
	}
	return -1;
}

extern "C" void ocio_proc_free(struct ocio_proc *p) { delete p; }

extern "C" const char *ocio_version(void)
{
	try {
		return OCIO::GetVersion();
	} catch (...) {
		return "unknown";
	}
}
