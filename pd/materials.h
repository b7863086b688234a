/* The list of peridynamic materials (an X-macro, as libCEED's backend list): a new material is
 * one file pd/material_<id>.c defining pf_pd_material_<id>, and one line here. */
PF_PD_MATERIAL(pmb)
PF_PD_MATERIAL(lps)
PF_PD_MATERIAL(elastic_plastic)
