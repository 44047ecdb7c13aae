!> Models used by several test modules.
module fsym_test_models
    use fsym, only: kepler_model_t
    implicit none
    private
    public :: wrapped_kepler_t

    !> The Kepler model seen through an extension: the integrator then takes the general
    !> path, not the kernel's specialised Kepler path.
    type, extends(kepler_model_t) :: wrapped_kepler_t
    end type wrapped_kepler_t

end module fsym_test_models
