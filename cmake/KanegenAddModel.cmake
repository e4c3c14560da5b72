# kanegen_add_model: written with the generator
