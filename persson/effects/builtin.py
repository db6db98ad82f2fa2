"""Built-in effects (being written)."""
Adhesion = FlashTemperature = Microtexture = StrainSoftening = Wet = None
