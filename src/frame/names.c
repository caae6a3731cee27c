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

const char *tg_aov_name(tg_aov aov)
{
    return (unsigned)aov < TG_AOV_COUNT ? aov_names[aov] : "?";
}

int tg_aov_from_name(const char *name)
{
    int i;
    for (i = 0; i < TG_AOV_COUNT; i++)
        if (strcmp(name, aov_names[i]) == 0) return i;
    return -1;
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
    return (unsigned)t < TG_TECH_COUNT ? technique_names[t] : "?";
}

int tg_technique_from_name(const char *name)
{
    int i;
    for (i = 0; i < TG_TECH_COUNT; i++)
        if (strcmp(name, technique_names[i]) == 0) return i;
    return -1;
}
