"""SI units of the quantities in snapshots, histories and summaries.

`unit(name)` gives the unit of a field or column name as the files spell it: exact names first
("normal_stress"), then a per-phase fluid field "<phase>_<quantity>" ("gas_pressure", "air_alpha",
"tungsten_granular_temperature"), then a component "<quantity>_x|y|z" ("force_x", "velocity_y"). "-" is
dimensionless; None means the name is not known. Quantities of 1D and 2D runs integrated over the domain (mass,
energy, force, momentum) are those of a slice 1 m deep (2D) or of 1 m^2 cross-section (1D), as the solvers count
them.
"""

# Per-phase fluid fields: "<phase>_<quantity>" and "mixture_<quantity>".
PHASE_QUANTITIES = {
    "alpha": "-",                       # volume fraction
    "density": "kg/m^3",
    "velocity": "m/s",
    "pressure": "Pa",
    "temperature": "K",
    "granular_temperature": "m^2/s^2",  # dispersed phase
}

UNITS = dict(PHASE_QUANTITIES)
UNITS.update({
    # geometry and metadata
    "time": "s", "step": "-", "cycle": "-", "dt": "s",
    "coordinates": "m", "connectivity": "-", "origin": "m", "spacing": "m", "cells": "-",
    # fluid
    "embedded_category": "-",           # 0 fluid, 1 fluid-cut, 2 solid-cut, 3 ghost, 4 solid (paper Table 1)
    # solid snapshots (velocity is a node field)
    "viscosity": "Pa",                  # artificial viscosity q
    "energy": "J/kg",                   # specific internal energy
    "sound_speed": "m/s",
    "stress": "Pa",                     # Cauchy stress, xx xy xz yy yz zz
    "von_mises": "Pa",
    "plastic_strain": "-",
    "block": "-",                       # block index
    # interface snapshots (coupler/interface_NNNNNN.h5)
    "normal_velocity": "m/s",
    "normal_stress": "Pa",              # n.sigma.n, tension positive
    "impedance": "Pa s/m",              # rho c; inf for a rigid solid
    "wetted": "-",
    "normal": "-",                      # unit, out of the solid
    # coupler/interface_history.csv (per cycle)
    "force": "N",
    "centre": "m",
    # coupler/timing.csv (wall time per cycle)
    "wall": "s", "solid": "s", "fluid": "s", "coupler": "s", "output": "s", "comm": "s",
    # solid/block_history.csv
    "mass": "kg",
    "kinetic_energy": "J",
    "internal_energy": "J",
    "plastic_work": "J",
    "max_von_mises": "Pa",
    "max_plastic_strain": "-",
    # fluid/fluid_interface_NNNNNN.csv (embedded interface segments)
    "i": "-", "j": "-", "k": "-",
    "cx": "m", "cy": "m", "cz": "m",
    "nx": "-", "ny": "-", "nz": "-",
    "area": "m^2",
    "vx": "m/s", "vy": "m/s", "vz": "m/s",
    # piston.csv of the Python rigid piston
    "x": "m", "v": "m/s",
    # summaries
    "momentum": "kg m/s",
    "wall_time_s": "s",
    "final_time": "s", "t_end": "s",
})

_COMPONENTS = ("_x", "_y", "_z")


def unit(name):
    """SI unit of a field or column name ("gas_pressure" -> "Pa", "force_x" -> "N"), or None if unknown."""
    if name in UNITS:
        return UNITS[name]
    parts = name.split("_")
    for i in range(1, len(parts)):  # longest known quantity after a phase name
        quantity = "_".join(parts[i:])
        if quantity in PHASE_QUANTITIES:
            return PHASE_QUANTITIES[quantity]
    for suffix in _COMPONENTS:
        if name.endswith(suffix) and len(name) > len(suffix):
            return unit(name[:-len(suffix)])
    return None
