! gyro_api: gyro's C API (gyro/gyro.h) for Fortran 2008 programs, through ISO_C_BINDING.
!
!   use gyro_api
!   type(gyro_config) :: cfg          ! a configuration, its fields set by name
!   type(gyro_model) :: model         ! the report's gyro model, in real(c_double) or real(c_float)
!   call cfg%init(GYRO_MODEL_CONFIG)
!   call cfg%set('pitch_inertia', 2.25d0)
!   status = model%create(c_double)   ! or c_float
!   status = model%configure(cfg, why)
!   status = model%uncage(R_earth_to_body, body_rate)
!   status = model%step_slew(dt, R_earth_to_body, slew, spin_hz)   ! arrays of the model's kind
!   call model%gimbal(angles)
!   call model%destroy()
!
! Matrices are Fortran's R(i, j) (this module transposes them to gyro.h's rows). Statuses are
! gyro.h's integers; gyro_status_text() says what one means. docs/embedding.md has an example.
module gyro_api
  use, intrinsic :: iso_c_binding
  implicit none
  private

  public :: c_float, c_double, c_int
  public :: gyro_config, gyro_model, gyro_status_text, gyro_status_name, gyro_nearest_rotation
  public :: gyro_angular_momentum, gyro_rotor_parameters, gyro_rotor_modes, gyro_compute_modes
  public :: gyro_initg_step, gyro_transition, gyro_make_transition, gyro_advance
  public :: gyro_report_sample, gyro_report_sample_get, gyro_frame_rotation, gyro_abi_version

  ! gyro.h's values used here (checked against the library by the module's test).
  integer(c_int), parameter, public :: GYRO_OK = 0, GYRO_OUT_OF_RANGE = 7, GYRO_OUT_OF_MEMORY = 69
  integer(c_int), parameter, public :: GYRO_ABI_WRITTEN_FOR = 1  ! gyro.h's GYRO_ABI_VERSION
  integer(c_int), parameter, public :: GYRO_MODEL_CONFIG = 1, GYRO_PLANT_CONFIG = 2
  integer(c_int), parameter, public :: GYRO_FLAG_GIMBAL_LIMIT = 1, GYRO_FLAG_SMALL_ANGLE = 2

  ! gyro.h's plain structs.
  type, bind(c) :: gyro_rotor_parameters
    real(c_double) :: pitch_inertia = 0, yaw_inertia = 0, friction = 0, angular_momentum = 0
  end type
  type, bind(c) :: gyro_rotor_modes
    real(c_double) :: alpha_1_s = 0, beta_squared_1_s2 = 0, beta_rad_s = 0, natural_rate_rad_s = 0
    real(c_double) :: slow_decay_rate_1_s = 0, fast_decay_rate_1_s = 0, nutation_hz = 0
    integer(c_int) :: regime = 0
  end type
  type, bind(c) :: gyro_transition
    real(c_double) :: coefficients(17) = 0
  end type
  type, bind(c) :: gyro_report_sample
    real(c_double) :: spin_hz = 0, body_rate_rad_s(2) = 0, slew_rate_rad_s(2) = 0, initg_step_s = 0
    integer(c_int) :: steps = 0
  end type
  type, bind(c) :: refusal_c
    integer(c_int) :: status
    type(c_ptr) :: field
    real(c_double) :: value, bound
    integer(c_int) :: relation
    type(c_ptr) :: bound_name, rule
  end type
  type, bind(c) :: step_input_d
    real(c_double) :: dt_s, r(9), body_accel(2), spin_hz, body_rate(3)
  end type
  type, bind(c) :: step_input_f
    real(c_float) :: dt_s, r(9), body_accel(2), spin_hz, body_rate(3)
  end type

  ! A configuration (gyro_model_config or gyro_plant_config) held for the C API, its fields set
  ! by their gyro.h names ("errors.pitch.static_drift_rad_s").
  type :: gyro_config
    integer(c_int) :: kind = 0
    real(c_double), allocatable :: storage(:)
  contains
    procedure :: init => config_init
    procedure :: set_scalar => config_set_scalar
    procedure :: set_vector => config_set_vector
    generic :: set => set_scalar, set_vector
    procedure :: set_choice => config_set_choice
    procedure :: get => config_get
  end type

  ! GyroModel on the heap, in double (kind c_double) or float (c_float).
  type :: gyro_model
    type(c_ptr) :: handle = c_null_ptr
    integer :: real_kind = 0
  contains
    procedure :: create => model_create
    procedure :: destroy => model_destroy
    procedure :: configure => model_configure
    procedure :: uncage_d, uncage_f
    generic :: uncage => uncage_d, uncage_f
    procedure :: step_slew_d, step_slew_f
    generic :: step_slew => step_slew_d, step_slew_f
    procedure :: gimbal_d, gimbal_f
    generic :: gimbal => gimbal_d, gimbal_f
    procedure :: rate_d, rate_f
    generic :: rate => rate_d, rate_f
    procedure :: isaf_angle_d, isaf_angle_f
    generic :: isaf_angle => isaf_angle_d, isaf_angle_f
    procedure :: r_earth_to_gyro_d, r_earth_to_gyro_f
    generic :: r_earth_to_gyro => r_earth_to_gyro_d, r_earth_to_gyro_f
    procedure :: flags => model_flags
    procedure, private :: require => model_require
  end type

  interface gyro_nearest_rotation
    module procedure nearest_rotation_d, nearest_rotation_f
  end interface
  interface gyro_angular_momentum
    procedure angular_momentum_d, angular_momentum_f
  end interface

  ! gyro.h, as called from here.
  interface
    function c_strlen(s) bind(c, name='strlen')
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: c_strlen
    end function
    function gyro_abi_version() bind(c, name='gyro_abi_version')
      import :: c_int
      integer(c_int) :: gyro_abi_version
    end function
    function c_status_text(s) bind(c, name='gyro_status_text')
      import :: c_int, c_ptr
      integer(c_int), value :: s
      type(c_ptr) :: c_status_text
    end function
    function c_status_name(s) bind(c, name='gyro_status_name')
      import :: c_int, c_ptr
      integer(c_int), value :: s
      type(c_ptr) :: c_status_name
    end function
    function c_refusal_text(r, buf, n) bind(c, name='gyro_refusal_text')
      import :: refusal_c, c_char, c_size_t, c_int
      type(refusal_c), intent(in) :: r
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_refusal_text
    end function
    function c_config_size(kind) bind(c, name='gyro_config_size')
      import :: c_int, c_size_t
      integer(c_int), value :: kind
      integer(c_size_t) :: c_config_size
    end function
    function c_config_init(kind, config) bind(c, name='gyro_config_init')
      import :: c_int, c_ptr
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      integer(c_int) :: c_config_init
    end function
    function c_config_set(kind, config, name, values, n) bind(c, name='gyro_config_set')
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), intent(in) :: values(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_config_set
    end function
    function c_config_get(kind, config, name, values, n) bind(c, name='gyro_config_get')
      import :: c_int, c_ptr, c_char, c_double, c_size_t
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*)
      real(c_double), intent(out) :: values(*)
      integer(c_size_t), value :: n
      integer(c_int) :: c_config_get
    end function
    function c_config_set_choice(kind, config, name, choice) bind(c, name='gyro_config_set_choice')
      import :: c_int, c_ptr, c_char
      integer(c_int), value :: kind
      type(c_ptr), value :: config
      character(kind=c_char), intent(in) :: name(*), choice(*)
      integer(c_int) :: c_config_set_choice
    end function
    function c_model_create_d() bind(c, name='gyro_model_d_create')
      import :: c_ptr
      type(c_ptr) :: c_model_create_d
    end function
    function c_model_create_f() bind(c, name='gyro_model_f_create')
      import :: c_ptr
      type(c_ptr) :: c_model_create_f
    end function
    subroutine c_model_destroy_d(m) bind(c, name='gyro_model_d_destroy')
      import :: c_ptr
      type(c_ptr), value :: m
    end subroutine
    subroutine c_model_destroy_f(m) bind(c, name='gyro_model_f_destroy')
      import :: c_ptr
      type(c_ptr), value :: m
    end subroutine
    function c_model_configure_d(m, config, refusal) bind(c, name='gyro_model_d_configure')
      import :: c_ptr, c_int, refusal_c
      type(c_ptr), value :: m, config
      type(refusal_c), intent(out) :: refusal
      integer(c_int) :: c_model_configure_d
    end function
    function c_model_configure_f(m, config, refusal) bind(c, name='gyro_model_f_configure')
      import :: c_ptr, c_int, refusal_c
      type(c_ptr), value :: m, config
      type(refusal_c), intent(out) :: refusal
      integer(c_int) :: c_model_configure_f
    end function
    function c_model_flags_d(m) bind(c, name='gyro_model_d_flags')
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: m
      integer(c_int32_t) :: c_model_flags_d
    end function
    function c_model_flags_f(m) bind(c, name='gyro_model_f_flags')
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: m
      integer(c_int32_t) :: c_model_flags_f
    end function
    function angular_momentum_d(spin_hz, spin_inertia) bind(c, name='gyro_angular_momentum_d')
      import :: c_double
      real(c_double), value :: spin_hz, spin_inertia
      real(c_double) :: angular_momentum_d
    end function
    function angular_momentum_f(spin_hz, spin_inertia) bind(c, name='gyro_angular_momentum_f')
      import :: c_float
      real(c_float), value :: spin_hz, spin_inertia
      real(c_float) :: angular_momentum_f
    end function
    function gyro_compute_modes(p, modes) bind(c, name='gyro_compute_modes_d')
      import :: c_int, gyro_rotor_parameters, gyro_rotor_modes
      type(gyro_rotor_parameters), intent(in) :: p
      type(gyro_rotor_modes), intent(out) :: modes
      integer(c_int) :: gyro_compute_modes
    end function
    function gyro_initg_step(p, step_s) bind(c, name='gyro_initg_step_d')
      import :: c_int, c_double, gyro_rotor_parameters
      type(gyro_rotor_parameters), intent(in) :: p
      real(c_double), intent(inout) :: step_s
      integer(c_int) :: gyro_initg_step
    end function
    function gyro_make_transition(p, dt_s, out) bind(c, name='gyro_make_transition_d')
      import :: c_int, c_double, gyro_rotor_parameters, gyro_transition
      type(gyro_rotor_parameters), intent(in) :: p
      real(c_double), value :: dt_s
      type(gyro_transition), intent(inout) :: out
      integer(c_int) :: gyro_make_transition
    end function
    function gyro_advance(tr, torque, state) bind(c, name='gyro_advance_d')
      import :: c_int, c_double, gyro_transition
      type(gyro_transition), intent(in) :: tr
      real(c_double), intent(in) :: torque(2)
      real(c_double), intent(inout) :: state(4)
      integer(c_int) :: gyro_advance
    end function
    function c_report_sample_get(out, config) bind(c, name='gyro_report_sample_get')
      import :: c_int, c_ptr, gyro_report_sample
      type(gyro_report_sample), intent(out) :: out
      type(c_ptr), value :: config
      integer(c_int) :: c_report_sample_get
    end function
    function c_frame_rotation(axis, angle, r) bind(c, name='gyro_frame_rotation_d')
      import :: c_int, c_double
      integer(c_int), value :: axis
      real(c_double), value :: angle
      real(c_double), intent(out) :: r(9)
      integer(c_int) :: c_frame_rotation
    end function
  end interface

contains

  ! A C string (static in the library) as a Fortran string.
  function from_c(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function

  function to_c(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: c
    c = trim(s) // c_null_char
  end function

  function gyro_status_text(status) result(s)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: s
    s = from_c(c_status_text(status))
  end function

  function gyro_status_name(status) result(s)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: s
    s = from_c(c_status_name(status))
  end function

  ! ------------------------------------------------------------------------------------------
  subroutine config_init(self, kind)
    class(gyro_config), intent(inout), target :: self
    integer(c_int), intent(in) :: kind
    integer(c_int) :: status
    self%kind = kind
    if (allocated(self%storage)) deallocate(self%storage)
    allocate(self%storage((c_config_size(kind) + 7) / 8 + 1))
    status = c_config_init(kind, c_loc(self%storage))
    if (status /= GYRO_OK) error stop 'gyro_config%init: no such configuration kind'
  end subroutine

  ! Sets a number (or a choice by its index); the status says if the name is unknown.
  function config_set_scalar(self, name, value) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: value
    integer(c_int) :: status
    status = c_config_set(self%kind, c_loc(self%storage), to_c(name), [value], 1_c_size_t)
  end function

  function config_set_vector(self, name, values) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: values(:)
    integer(c_int) :: status
    status = c_config_set(self%kind, c_loc(self%storage), to_c(name), values, size(values, kind=c_size_t))
  end function

  function config_set_choice(self, name, choice) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name, choice
    integer(c_int) :: status
    status = c_config_set_choice(self%kind, c_loc(self%storage), to_c(name), to_c(choice))
  end function

  function config_get(self, name, values) result(status)
    class(gyro_config), intent(inout), target :: self
    character(len=*), intent(in) :: name
    real(c_double), intent(out) :: values(:)
    integer(c_int) :: status
    status = c_config_get(self%kind, c_loc(self%storage), to_c(name), values, size(values, kind=c_size_t))
  end function

  ! ------------------------------------------------------------------------------------------
  ! A new model computing in real_kind (c_double or c_float); GYRO_OUT_OF_MEMORY if none.
  function model_create(self, real_kind) result(status)
    class(gyro_model), intent(inout) :: self
    integer, intent(in) :: real_kind
    integer(c_int) :: status
    if (gyro_abi_version() /= GYRO_ABI_WRITTEN_FOR) error stop 'gyro_api: libgyro has another ABI than this module'
    call self%destroy()
    self%real_kind = real_kind
    if (real_kind == c_double) then
      self%handle = c_model_create_d()
    else if (real_kind == c_float) then
      self%handle = c_model_create_f()
    else
      status = GYRO_OUT_OF_RANGE
      return
    end if
    status = merge(GYRO_OK, GYRO_OUT_OF_MEMORY, c_associated(self%handle))
  end function

  subroutine model_destroy(self)
    class(gyro_model), intent(inout) :: self
    if (.not. c_associated(self%handle)) return
    if (self%real_kind == c_double) then
      call c_model_destroy_d(self%handle)
    else
      call c_model_destroy_f(self%handle)
    end if
    self%handle = c_null_ptr
  end subroutine

  ! Configures from a GYRO_MODEL_CONFIG; on a refusal, `why` (if present) says which field, its
  ! value and the bound.
  function model_configure(self, config, why) result(status)
    class(gyro_model), intent(inout) :: self
    class(gyro_config), intent(in), target :: config
    character(len=:), allocatable, intent(out), optional :: why
    integer(c_int) :: status, n
    type(refusal_c) :: r
    character(kind=c_char) :: buf(512)
    integer :: i
    if (self%real_kind == c_double) then
      status = c_model_configure_d(self%handle, c_loc(config%storage), r)
    else
      status = c_model_configure_f(self%handle, c_loc(config%storage), r)
    end if
    if (.not. present(why)) return
    n = c_refusal_text(r, buf, size(buf, kind=c_size_t))
    n = min(n, size(buf) - 1)
    allocate(character(len=n) :: why)
    do i = 1, n
      why(i:i) = buf(i)
    end do
  end function

  ! GYRO_FLAG_GIMBAL_LIMIT, GYRO_FLAG_SMALL_ANGLE.
  function model_flags(self) result(flags)
    class(gyro_model), intent(in) :: self
    integer(c_int32_t) :: flags
    if (self%real_kind == c_double) then
      flags = c_model_flags_d(self%handle)
    else
      flags = c_model_flags_f(self%handle)
    end if
  end function

  ! ------------------------------------------------------------------------------------------
  ! A body turning by `angle` about its own y (axis 2) or z (axis 3): R_new = R_axis R_old.
  function gyro_frame_rotation(axis, angle, r) result(status)
    integer, intent(in) :: axis
    real(c_double), intent(in) :: angle
    real(c_double), intent(out) :: r(3, 3)
    integer(c_int) :: status
    real(c_double) :: rows(9)
    status = c_frame_rotation(int(axis - 1, c_int), angle, rows)
    if (status == GYRO_OK) r = transpose(reshape(rows, [3, 3]))
  end function

  ! The report's sample (gyro/report_sample.hpp): its facts, and its gyro into `config`.
  function gyro_report_sample_get(sample, config) result(status)
    type(gyro_report_sample), intent(out) :: sample
    type(gyro_config), intent(inout), target :: config
    integer(c_int) :: status
    call config%init(GYRO_MODEL_CONFIG)
    status = c_report_sample_get(sample, c_loc(config%storage))
  end function

  ! Checks the arguments' kind against the model's.
  subroutine model_require(self, real_kind)
    class(gyro_model), intent(in) :: self
    integer, intent(in) :: real_kind
    if (self%real_kind /= real_kind) error stop 'gyro_model: arguments of another REAL kind than the model'
  end subroutine

#define CN(x) 'gyro_model_'//SUFFIX//'_'//x
#define STEP_INPUT step_input_d
#define WP c_double
#define K(x) x/**/_d
#define SUFFIX 'd'
#include "gyro_api_kind.inc"
#undef STEP_INPUT
#undef WP
#undef K
#undef SUFFIX
#define STEP_INPUT step_input_f
#define WP c_float
#define K(x) x/**/_f
#define SUFFIX 'f'
#include "gyro_api_kind.inc"

end module gyro_api
