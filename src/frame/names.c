/* SPDX-License-Identifier: MIT */
/*
 * names.c - the names a person types for outputs and techniques.
 */
#include <string.h>
#include "../tinygi.h"

static const char *const aov_names[TG_AOV_COUNT] = {
    "color", "depth", "normal", "albedo", "ao", "bent", "cone", "near", "far",
    "direct", "irradiance", "motion"
};

static const char *const technique_names[TG_TECH_COUNT] = {
    "hbil", "gtao", "hbao", "ssao", "vo", "ssdo", "bentcone", "reference", "pathtrace", "ssilvb"
};

/* Name i of a table of count names ("?" outside it), and the index of a
 * name in it (-1 when absent). */
static const char *name_at(const char *const *names, int count, int i)
{
    return (unsigned)i < (unsigned)count ? names[i] : "?";
}

static int name_index(const char *const *names, int count, const char *name)
{
    int i;
    for (i = 0; i < count; i++)
        if (strcmp(name, names[i]) == 0) return i;
    return -1;
}

const char *tg_aov_name(tg_aov aov)
{
    return name_at(aov_names, TG_AOV_COUNT, (int)aov);
}

int tg_aov_from_name(const char *name)
{
    return name_index(aov_names, TG_AOV_COUNT, name);
}

int tg_aov_channels(tg_aov aov)
{
    switch (aov) {
    case TG_AOV_DEPTH: case TG_AOV_AO: case TG_AOV_CONE: return 1;
    default: return 3;
    }
}

const char *tg_technique_name(tg_technique t)
{
    return name_at(technique_names, TG_TECH_COUNT, (int)t);
}

int tg_technique_from_name(const char *name)
{
    return name_index(technique_names, TG_TECH_COUNT, name);
}
