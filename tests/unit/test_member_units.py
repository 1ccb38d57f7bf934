"""The one unit rule of a dataset variable whose members (load effects, sensors) have several units
(``vbikit.outputs.member_units``)."""
def test_member_units_give_one_parseable_unit_or_the_coordinate_of_each():
    """A variable over load effects or sensors of one unit has it; of several, no ``units`` (CF allows one parseable
    unit a variable; a packed "N m; m; N" none reads) and ``units_by_<dim>`` naming the coordinate of each's."""
    from vbikit.outputs import member_units

    assert member_units(["N m", "N m"], "load_effect", "load_effect_units") == {"units": "N m"}
    assert member_units(["N m", "m", "N"], "load_effect", "load_effect_units") == {"units_by_load_effect": "load_effect_units"}
    assert member_units(["m s-2", "m"], "sensor", "sensor_units") == {"units_by_sensor": "sensor_units"}
