/* The list of damage laws (an X-macro, as pd/materials.h): a new law is one file
 * pd/damage_<id>.c defining pf_pd_damage_<id>, and one line here. The order is that of the
 * known names in messages. */
PF_PD_DAMAGE_LAW(none)
PF_PD_DAMAGE_LAW(critical_stretch)
PF_PD_DAMAGE_LAW(silling_askari)
PF_PD_DAMAGE_LAW(critical_energy)
PF_PD_DAMAGE_LAW(softening)
